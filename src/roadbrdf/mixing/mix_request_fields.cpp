// The field table of MixRequest (core/request_fields.h): `roadbrdf mix`'s options and the keyword
// arguments of Python's roadbrdf.mix.
#include <string>
#include <vector>

#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/mixing/mix_request.h"

namespace roadbrdf::mixing {

RequestFields<MixRequest> MixRequest::fields() {
  using R = MixRequest;
  // A help listing the names a field accepts, kept for the table's string views.
  static const std::string method_help = "Mixing method: " + names_text<Method>() + ", or all";
  static const std::vector<RequestField<R>> table = [] {
    std::vector<RequestField<R>> rows = {
        {"formulation", "FORMULATION", "", "Formulation file (JSON, see data/examples/formulations/README.md)",
         &R::formulation, FileRole::input, true},
        {"data", "--data", "", "Measured BRDF of the mixed sample (CSV): compare the methods on it", &R::data,
         FileRole::input},
    };
    for (const RequestField<R>& row : dataset_read_fields<R>()) rows.push_back(row);
    const std::vector<RequestField<R>> own = {
        {"method", "--method", "", method_help, &R::method},
        {"folds", "--folds", "", "Cross-validation folds over geometries", &R::folds},
        {"seed", "--seed", "", "Seed of the geometry shuffle for the folds", &R::seed},
        {"per_wavelength", "--per-wavelength", "", "fitted: one weight set per wavelength (default: one for all)",
         &R::per_wavelength},
        {"uncertainty", "--uncertainty", "",
         "areal, mastic, hapke: carry the components' fit covariances into MIX.json (albedo and rtable of it then "
         "give uncertainties; the albedo becomes much slower)",
         &R::uncertainty},
        {"sum_to_one", "--sum-to-one", "", "fitted, shadowed: constrain the weights to sum to one", &R::sum_to_one},
        {"binder_coverage", "--binder-coverage", "",
         "areal: fraction of the surface covered by binder, overriding the formulation", &R::binder_coverage},
        {"mastic_fraction", "--mastic-fraction", "", "mastic: area fraction of the mastic, overriding the formulation",
         &R::mastic_fraction},
        {"use_sigma", "--no-sigma-weights", "",
         "fitted, shadowed: weight residuals by 1/sigma^2 when the data give sigma (on by default; the switch "
         "ignores sigma)",
         &R::use_sigma},
        {"residuals", "--residuals", "",
         "With data: write the held-out residuals per method, geometry and wavelength (CSV, see docs/mixing.md)",
         &R::residuals, FileRole::output},
        {"reference", "--reference", "",
         "Fit file of the measured mixture: the albedo difference column compares with it", &R::reference,
         FileRole::input},
        {"cross_sections", "--cross-sections", "",
         "hapke: calibrated cross-section factors per end-member (file of `roadbrdf mix-calibrate`)",
         &R::cross_sections, FileRole::input},
        {"output", "-o,--output", "", "Output MIX.json (format: src/roadbrdf/mixing/mix_file.h)", &R::output,
         FileRole::output},
    };
    rows.insert(rows.end(), own.begin(), own.end());
    return rows;
  }();
  return table;
}

}  // namespace roadbrdf::mixing
