// Road-marking figures as the front ends ask for them (`roadbrdf marking`, roadbrdf.marking in
// Python), made by the request contract (core/request_fields.h): the request with its field table and
// its one validation, and the result with its value, notes and warnings, summary and JSON.
//
// The source is a fit file or a MIX.json (read by the modelfile layer), a model name with its
// parameters, or a measured dataset file (CSV, OpenMATERIAL 3D).
// A model gives R_L, Q_d and beta (marking.h); measured data give R_L and beta where they reach the
// geometry (within `tolerance`), and an error naming the fit to make where they do not.
//
// With a `pavement` and/or an `installation` the result also holds the luminance contrast of the
// marking against that pavement (marking_contrast.h); it is computed in the lighting module, which
// reads headlamps, installations and pavements, and is handed to marking() as a function.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/core/request_fields.h"
#include "roadbrdf/modelfile/model_source.h"
#include "roadbrdf/photometry/marking.h"
#include "roadbrdf/photometry/marking_contrast.h"

namespace roadbrdf::photometry {

struct MarkingRequest {
  std::string source;                   // FIT.json | MIX.json | MODEL | DATA file
  std::vector<std::string> parameters;  // NAME=VALUE of a model given by name
  std::vector<std::string> options;     // NAME=VALUE model options
  std::string fit;                      // which fit of a fit file / method of a MIX.json ("" = best)
  std::string illuminant;               // "" = CIE A; "A", "D65" or a lamp spectrum file
  std::optional<double> wavelength;     // [nm]: the figures at one wavelength instead of V(lambda) x illuminant
  double illumination_angle = kMarkingIlluminationAngleDeg;  // epsilon above the road [deg]
  double observation_angle = kMarkingObservationAngleDeg;    // alpha above the road [deg]
  double tolerance = 1.0;  // measured data: largest distance to a measured geometry [deg]
  // The contrast against a pavement (marking_contrast.h).
  std::string pavement;                                // CIE table, r-table file, FIT.json, MIX.json or MODEL
  std::vector<std::string> pavement_parameters;        // NAME=VALUE of a pavement model given by name
  std::string pavement_fit;                            // which fit / method of the pavement's file ("" = best)
  std::string headlamp;                                // luminaire file of the vehicle's headlamp (IES, EULUMDAT)
  double headlamp_down_plane = kHeadlampDownPlaneDeg;  // the headlamp file's C-plane that points down [deg]
  std::string installation;                            // road-lighting installation file

  // Whether the request asks for the contrast against a pavement.
  bool wants_contrast() const { return !pavement.empty() || !installation.empty(); }

  static std::span<const RequestField<MarkingRequest>> fields();
  // Throws FieldError.
  void validate() const;
  // Whether the geometry is EN 1436's (the classes apply to it only).
  bool standard_geometry() const;
};

struct MarkingResult {
  std::string source_kind;  // "fit", "model" or "data"
  std::string model;        // the model's name (fit, model)
  nlohmann::json weighting;
  std::optional<double> rl, qd, qd_error, beta;  // [mcd m^-2 lx^-1], beta [1]; none where unknown
  std::optional<double> rl_nearest_distance;     // data: distance to the nearest measured geometry [deg]
  std::optional<std::size_t> rl_points;          // data: measured geometries combined
  std::optional<double> beta_nearest_distance;
  std::string rl_class, qd_class;           // EN 1436 classes; "" when not at the standard geometry or unknown
  std::optional<MarkingContrast> contrast;  // against the request's pavement, when asked for
  double illumination_angle = 0.0, observation_angle = 0.0;
  Diagnostics diagnostics;

  nlohmann::json to_json() const;
  std::string summary_text() const;
};

// The contrast part of a request (lighting/marking_contrast.h): the marking's model (null for measured
// data) and its figures in, the contrast out; notes and warnings go to `diagnostics`.
using MarkingContrastFunction =
    std::function<MarkingContrast(const MarkingRequest& request, const SpectralModel* marking_model,
                                  const MarkingResult& figures, Diagnostics& diagnostics)>;

// The figures of the request's source, and with a pavement or an installation its contrast computed by
// `contrast` (a request that asks for one without it is a FieldError). Throws FieldError / FileError /
// InputError.
MarkingResult marking(const MarkingRequest& request, const MarkingContrastFunction& contrast = {});

}  // namespace roadbrdf::photometry
