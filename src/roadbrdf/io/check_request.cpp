#include "roadbrdf/io/check_request.h"

#include <fmt/core.h>

#include <string_view>
#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/io/calibration.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/dataset_read_fields.h"

namespace roadbrdf {

RequestFields<CheckOptions> CheckOptions::fields() {
  using R = CheckOptions;
  static const RequestField<R> rows[] = {
      {"panel_reflectance", "--panel-reflectance", "",
       "The dataset is a reference panel: compare it with rho/pi, rho from this file (wavelength [nm], "
       "reflectance [, sigma])",
       &R::panel_file, FileRole::input},
      {"tolerance", "--tolerance", "deg", "Angle tolerance of reciprocity pairs", &R::angle_tolerance_deg},
      {"exact_reciprocity", "--exact-reciprocity", "",
       "Pair geometries by exchanged directions (default: exchanged zenith angles, same |dphi|: isotropic)",
       &R::exact_reciprocity},
      {"reciprocity_threshold", "--reciprocity-threshold", "",
       "Relative disagreement above which a reciprocity pair is flagged", &R::reciprocity_threshold},
      {"snr_threshold", "--snr-threshold", "", "Signal-to-noise ratio below which a band is noisy", &R::snr_threshold},
      {"noise_window", "--noise-window", "", "Wavelengths on each side pooled in the noise estimate", &R::noise_window},
      {"neighbours", "--neighbours", "", "Angular neighbours compared with each geometry", &R::neighbours},
      {"outlier_threshold", "--outlier-threshold", "", "Robust score above which a geometry is an outlier",
       &R::outlier_threshold},
      {"outlier_min_ratio", "--outlier-min-ratio", "", "Minimum ratio to the neighbours' median for an outlier",
       &R::outlier_min_ratio},
      {"specular_window", "--specular-window", "deg",
       "Angle from the mirror direction within which a bright geometry is a specular peak, not an outlier",
       &R::specular_cone_deg},
      {"listed_outliers", "--listed-outliers", "", "Outliers listed in the text report (all of them in the JSON)",
       &R::listed_outliers},
  };
  return rows;
}

QualityOptions CheckOptions::quality_options() const {
  QualityOptions o = *this;
  o.validate();
  if (!panel_file.empty()) o.panel_reflectance = read_panel_reflectance(panel_file);
  return o;
}

RequestFields<CheckRequest> CheckRequest::fields() {
  using R = CheckRequest;
  static const std::vector<RequestField<R>> table = [] {
    std::vector<RequestField<R>> rows = {
        {"path", "DATA", "", "Dataset CSV (wide or long)", &R::path, FileRole::input, true},
    };
    for (const RequestField<R>& row : dataset_read_fields<R>()) rows.push_back(row);
    for (const RequestField<R>& row : fields_of_base<R, CheckOptions>()) rows.push_back(row);
    return rows;
  }();
  return table;
}

namespace {

// The receiver solid angles of an OpenMATERIAL 3D file (io/openmaterial3d.h), kept in the metadata
// under this prefix and the wavelength.
constexpr std::string_view kSolidAngle = "receiver_solid_angle_sr.";

}  // namespace

nlohmann::json CheckResult::to_json() const {
  nlohmann::json j = quality_report_json(data, report);
  j["file"] = file.empty() ? nlohmann::json(nullptr) : nlohmann::json(file);
  nlohmann::json solid_angles = nlohmann::json::object();
  for (const auto& [key, value] : data.metadata) {
    if (key.rfind(kSolidAngle, 0) == 0) solid_angles[key.substr(kSolidAngle.size())] = value;
  }
  if (!solid_angles.empty()) j["receiver_solid_angles_sr"] = solid_angles;
  return j;
}

std::string CheckResult::summary_text() const {
  std::string text = quality_report_text(data, report);
  for (const auto& [key, value] : data.metadata) {
    if (key.rfind(kSolidAngle, 0) != 0) continue;
    text += fmt::format("receiver solid angle at {} nm: {} sr\n", key.substr(kSolidAngle.size()), value);
  }
  return text;
}

CheckResult quality_check(const CheckRequest& request, const std::function<void(const std::string&)>& warn) {
  if (request.path.empty()) throw FieldError("path", "give the dataset file");
  check_request_files(request);
  DatasetReadOptions read = request.options_for(request.path, {request.path});
  read.allow_missing = true;  // counted in the report
  read.warn = warn;
  const QualityOptions options = request.quality_options();
  CheckResult result;
  result.file = request.path;
  DatasetReadStats stats;
  result.data = read_dataset(request.path, read, stats);
  result.report = check_dataset(result.data, options, stats);
  return result;
}

CheckResult quality_check(const SpectralDataset& dataset, const CheckOptions& options) {
  CheckResult result;
  result.data = dataset;
  result.report = check_dataset(result.data, options.quality_options());
  return result;
}

}  // namespace roadbrdf
