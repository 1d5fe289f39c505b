// `roadbrdf lighting` / roadbrdf.lighting(): an installation file (installation.h) computed by the
// rules of EN 13201-3:2015 (calculation.h), its M class, energy indicators and least flux for a class
// (en13201.h), the light it sends upward (upward_light.h) and, for a surface with a BRDF, how far the
// luminance at each point's true observation angle differs from the r-table's alpha = 1 deg result.
// One request (core/request_fields.h contract), one result for both front ends.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>

#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/core/request_fields.h"
#include "roadbrdf/lighting/calculation.h"
#include "roadbrdf/lighting/en13201.h"
#include "roadbrdf/lighting/upward_light.h"

namespace roadbrdf::lighting {

struct LightingRequest {
  std::string installation;         // the installation file
  std::string surface;              // replaces the installation's surface (surface_from_text)
  std::string target_class;         // an M class: the least flux and power per km that meet it
  double operating_hours = 4000.0;  // [h per year] for D_E
  std::string map;                  // CSV of the grid values (optional output)

  static std::span<const RequestField<LightingRequest>> fields();
  // Throws FieldError.
  void validate() const;
};

// How the luminance from the BRDF at each point's true observation angle differs from the r-table
// method (alpha = 1 deg for every point, interpolated in the table).
struct AlphaVariation {
  double alpha_min_deg = 0.0, alpha_max_deg = 0.0;
  double L_av_true_alpha = 0.0, U_o_true_alpha = 0.0, U_l_true_alpha = 0.0;  // governing, as the r-table's
  double L_av_alpha_1 = 0.0;              // from the BRDF at alpha = 1 deg (the r-table's convention, no interpolation)
  double L_av_difference = 0.0;           // L_av_true_alpha / L_av - 1
  double max_point_difference = 0.0;      // largest |L_true / L_rtable - 1| over the points and observers
  double interpolation_difference = 0.0;  // L_av_alpha_1 / L_av - 1: the table's interpolation alone
};

struct LightingResult {
  Installation installation;
  std::string luminaire_name;
  double installed_flux_lm = 0.0;  // per luminaire (override or the file's)
  double power_per_luminaire_w = 0.0;
  RoadSurface surface;
  LightingFigures figures;
  ClassAssessment lighting_class;
  EnergyFigures energy;
  std::optional<LeastFlux> least_flux;
  UpwardLight upward;
  std::optional<AlphaVariation> alpha_variation;
  Diagnostics diagnostics;

  // The document `roadbrdf lighting --json` prints (governing figures at the top level).
  nlohmann::json to_json() const;
  std::string summary_text() const;
};

// Everything from an installation, its luminaire and surface already in memory.
struct LightingOptions {
  std::string target_class;  // "" = none
  double operating_hours = 4000.0;
};
LightingResult evaluate_installation(const Installation& installation, const Luminaire& luminaire,
                                     const RoadSurface& surface, const LightingOptions& options,
                                     Diagnostics diagnostics = {});

// The request's task: reads the files, computes, writes the map if asked. Throws FieldError /
// FileError / InputError.
LightingResult lighting(const LightingRequest& request);

// The grid as CSV: x_m, y_m, E_lx, then L_cd_m2 of each observer (lane), and with a BRDF the
// luminance at the true observation angle.
void write_lighting_map(const std::string& path, const LightingResult& result);

}  // namespace roadbrdf::lighting
