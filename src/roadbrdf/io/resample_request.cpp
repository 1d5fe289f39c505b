#include "roadbrdf/io/resample_request.h"

#include <fmt/core.h>

#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/range.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/dataset_read_fields.h"
#include "roadbrdf/io/quality.h"
#include "roadbrdf/io/resample.h"

namespace roadbrdf {

RequestFields<ResampleRequest> ResampleRequest::fields() {
  using R = ResampleRequest;
  static const std::string format_help = "Output format: " + names_text<DatasetFormat>() + " (default wide)";
  static const std::vector<RequestField<R>> table = [] {
    std::vector<RequestField<R>> rows = {
        {"data", "DATA", "", "Dataset CSV (wide or long)", &R::data, FileRole::input, true},
    };
    for (const RequestField<R>& row : dataset_read_fields<R>()) rows.push_back(row);
    const std::vector<RequestField<R>> own = {
        {"wavelengths", "--wavelengths", "nm",
         "Band edges START:STOP:STEP: bands [START, START+STEP], ... reported at their centres", &R::wavelengths,
         FileRole::none, true},
        {"drop", "--drop", "nm", "Leave out the bands overlapping FROM:TO (repeatable)", &R::drop},
        {"drop_noisy", "--drop-noisy", "", "Leave out the bands overlapping the noisy bands found by `check`",
         &R::drop_noisy},
        {"snr_threshold", "--snr-threshold", "",
         "Signal-to-noise ratio below which a band is noisy, for leaving out the noisy bands", &R::snr_threshold},
        {"format", "--format", "", format_help, &R::format},
        {"output", "-o,--output", "", "Output dataset CSV (default: standard output)", &R::output, FileRole::output},
    };
    rows.insert(rows.end(), own.begin(), own.end());
    return rows;
  }();
  return table;
}

void ResampleRequest::validate() const {
  if (data.empty()) throw FieldError("data", "give the dataset file");
  if (wavelengths.empty()) throw FieldError("wavelengths", "give the band edges");
  check_range_values(wavelengths, "wavelengths", wavelength_rules());
  for (const auto& [lower, upper] : drop) {
    if (!(lower > 0.0 && lower <= upper)) {
      throw FieldError("drop", fmt::format("'{:g}:{:g}': need 0 < FROM <= TO [nm]", lower, upper));
    }
  }
  if (!(snr_threshold >= 0.0)) throw FieldError("snr_threshold", fmt::format("must be >= 0, got {:g}", snr_threshold));
  parse_name<DatasetFormat>(format, "format");
}

SpectralDataset resample(const ResampleRequest& request, const std::function<void(const std::string&)>& warn) {
  request.validate();
  check_request_files(request);
  DatasetReadOptions read = request.options_for(request.data, {request.data});
  read.warn = warn;
  const SpectralDataset d = read_dataset(request.data, read);
  const WavelengthBands bands = bands_from_edges(request.wavelengths);
  std::vector<std::pair<double, double>> drop = request.drop;
  std::string noisy_text;
  if (request.drop_noisy) {
    QualityOptions o;
    o.snr_threshold = request.snr_threshold;
    for (const NoisyBand& b : check_dataset(d, o).noisy_bands) {
      drop.emplace_back(b.lower_nm, b.upper_nm);
      noisy_text += fmt::format("{}{}-{}", noisy_text.empty() ? "" : " ", b.lower_nm, b.upper_nm);
    }
  }
  SpectralDataset out = resample_dataset(d, bands, drop);
  if (!noisy_text.empty()) out.metadata["noisy_bands_nm"] = noisy_text;
  write_dataset_output(out, request.output, request.format);
  return out;
}

}  // namespace roadbrdf
