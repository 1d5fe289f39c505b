// The `luminaire` task: a luminaire photometry file read and summarised (name, flux, maximum
// intensity and its direction, light output ratios, symmetry), for `roadbrdf luminaire FILE` and
// `roadbrdf.luminaire(FILE)` (the request contract, core/request_fields.h).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/core/request_fields.h"
#include "roadbrdf/lighting/luminaire.h"
#include "roadbrdf/lighting/luminaire_flux.h"

namespace roadbrdf::lighting {

struct LuminaireRequest {
  std::string file;  // an EULUMDAT (.ldt) or IES LM-63 (.ies) file

  static RequestFields<LuminaireRequest> fields();
  void validate() const;
};

// The differences between the flux integrated from the intensities and the file's header flux
// that are reported as a warning (flux_mismatch): more than 2 %.
inline constexpr double kFluxTolerance = 0.02;

struct LuminaireSummary {
  Luminaire luminaire;
  LuminousFlux flux;        // integrated from the intensities [lm]
  double header_flux_lm;    // the luminaire's flux the header states [lm] (0: none)
  double max_intensity_cd;  // the largest tabulated intensity, and its direction
  double max_c_deg;
  double max_gamma_deg;
  double dlor;  // downward and upward flux / the lamps' flux (absolute photometry: / the luminaire's)
  double ulor;
  Diagnostics diagnostics;

  // Intensities per 1000 lm [cd/klm]: of the lamps' flux, or of the luminaire's for absolute
  // photometry (the unit of polar curves and of EULUMDAT files).
  double candela_per_klm_factor() const;
  std::string summary_text() const;
  // Every number of the summary, the metadata, the principal planes (C0, C90, C180, C270 in cd/klm
  // at the file's gamma angles) and the notes and warnings.
  nlohmann::json to_json() const;
};

// Reads request.file (validated) and summarises it; warns (flux_mismatch) when the integrated flux
// differs from the header's by more than kFluxTolerance.
LuminaireSummary luminaire_summary(const LuminaireRequest& request);

}  // namespace roadbrdf::lighting
