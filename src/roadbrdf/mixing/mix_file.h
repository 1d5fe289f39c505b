// MIX.json: what `roadbrdf mix` writes (read back as a SpectralModel by modelfile/mix_file_read.h).
//
// {
//   "format": "roadbrdf-mix", "version": 1,
//   "units": { ... one description per quantity ... },
//   "formulation": { "name": "F1", "file": "<path>", "components": [ { "name", "kind", "mass_percent",
//                    "density_g_cm3", "d_eff_mm" (used D, null if not needed), "coarse", "end_member" } ] },
//   "end_members": [ { "name": "bitumen", "fit": "<resolved fit file>", "fit_model": "" ,
//                      "model": "oren-nayar", "options": { "form": "full" } } ],
//   "data": "<measured mixture CSV>" | null, "folds": K | null,
//   "best": "<method with the lowest held-out RMSE>" | null (no data),
//   "methods": [ {
//       "method": "areal" | "fitted" | "mastic" | "hapke" | "shadowed",
//       "description": "...",
//       "model": "mixture-linear" | "mixture-hapke" | "mixture-shadowed",   (mixing/mixture_model.h)
//       "end_members": ["bitumen", ...],          // the mixture's end-members, in parameter order
//       "coarse": [false, true, ...],             // coarse flags (used by mixture-shadowed)
//       "wavelengths": [nm, ...],                 // [] when no end-member depends on wavelength
//       "parameters": { "<parameter name>": [value per wavelength (one value when [])], ... },
//       "stderr", "correlation", "fixed": the mixture's parameter covariance from its end-members'
//                                   fits (mixture_covariance.h), as a fit file stores a fit's; absent
//                                   when it has none (fitted, shadowed; an end-member without one)
//       "weights": { "<end-member>": value },     // summary (see MixResult::weights)
//       "formulation_weights": { ... } | null, "weight_distance": x | null, "weight_sum": x | null,
//       "settings": { "binder_coverage": ..., "shadowing": ..., ... },
//       "notes": [ "..." ],
//       "comparison": null | { "folds", "rmse", "relative_rmse", "rmse_in_sample", "relative_rmse_in_sample",
//                              "chi2_reduced" (held-out; null without sigma), "albedo", "albedo_reference",
//                              "albedo_difference" }
//   } ]
// }
// The "parameters" block has exactly the schema of a fit file's fit (models/spectral_model.h), with the
// mixture's parameter names (weight.<end-member>, ssa.<end-member>, shadowing, <end-member>.<parameter>).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "roadbrdf/mixing/mixing.h"
#include "roadbrdf/modelfile/mix_file_read.h"
#include "roadbrdf/modelfile/model_source.h"

namespace roadbrdf::mixing {

struct MixFileContent {
  const MixInputs* inputs = nullptr;
  std::vector<MixResult> results;
  std::vector<Comparison> comparisons;  // empty without data; else one per result, same order
  std::string data_path;
  int folds = 0;
};

// The MIX.json content (what write_mix_file writes).
nlohmann::ordered_json mix_file_json(const MixFileContent& content);

// Write atomically. Throws InputError / FileError.
void write_mix_file(const std::string& path, const MixFileContent& content);

}  // namespace roadbrdf::mixing
