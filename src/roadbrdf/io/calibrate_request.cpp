#include "roadbrdf/io/calibrate_request.h"

#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/io/calibration.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/dataset_read_fields.h"
#include "roadbrdf/io/manifest.h"

namespace roadbrdf {

RequestFields<CalibrateRequest> CalibrateRequest::fields() {
  using R = CalibrateRequest;
  static const std::string format_help = "Output format: " + names_text<DatasetFormat>() + " (default wide)";
  static const std::vector<RequestField<R>> rows = [] {
    std::vector<RequestField<R>> all = {
        {"sample", "SAMPLE", "", "Sample radiances, dataset CSV (any units; sigma_<nm> columns optional)", &R::sample,
         FileRole::input},
        {"reference", "--reference", "",
         "Reference-panel radiances: same geometries as the sample, or a single row used for every geometry",
         &R::reference, FileRole::input},
        {"manifest", "--manifest", "",
         "Instrument run: CSV of file,role (sample|white|dark) and angles, mapping .asd/.sed/.sig files to "
         "geometries (replaces the sample, reference and dark files; docs/data.md)",
         &R::manifest, FileRole::input},
    };
    const std::vector<RequestField<R>> instrument = instrument_fields<R>();
    all.insert(all.end(), instrument.begin(), instrument.end());
    const std::vector<RequestField<R>> reading = dataset_read_fields<R>();
    all.insert(all.end(), reading.begin(), reading.end());
    const RequestField<R> own[] = {
        {"dark", "--dark", "", "Dark signal: same geometries, or a single row (default: none)", &R::dark,
         FileRole::input},
        {"panel_reflectance", "--panel-reflectance", "",
         "Calibrated panel reflectance rho_ref: wavelength [nm], value [, sigma] (e.g. Spectralon_Num4.txt)",
         &R::panel_reflectance, FileRole::input, true},
        {"panel_brf", "--panel-brf", "",
         "Measured BRF of the panel at the measurement geometry (replaces rho_ref: non-Lambertian correction)",
         &R::panel_brf, FileRole::input},
        {"panel_brf_start", "--panel-brf-start", "nm", "First wavelength of a one-column panel BRF file",
         &R::panel_brf_start},
        {"panel_brf_step", "--panel-brf-step", "nm", "Wavelength step of a one-column panel BRF file",
         &R::panel_brf_step},
        {"format", "--format", "", format_help, &R::format},
        {"output", "-o,--output", "", "Output BRDF dataset CSV (default: standard output)", &R::output,
         FileRole::output},
    };
    all.insert(all.end(), std::begin(own), std::end(own));
    return all;
  }();
  return rows;
}

namespace {

SpectralDataset calibrated(const CalibrateRequest& request) {
  std::vector<FileArgument> inputs, outputs;
  file_arguments(request, CalibrateRequest::fields(), inputs, outputs);
  check_distinct_files(inputs, outputs);
  // A bad format name is refused before any work.
  static_cast<void>(parse_name<DatasetFormat>(request.format, "format"));
  if (!request.manifest.empty()) {
    if (!request.sample.empty() || !request.reference.empty() || !request.dark.empty()) {
      throw InputError(
          "`manifest` gives the sample, white reference and dark files: no `sample`, `reference` or `dark`");
    }
    const ManifestOptions options = request.manifest_options();
    // The panel BRF's own checks come before the run is read.
    const std::optional<spectra::Spectrum> brf =
        read_panel_brf(request.panel_brf, request.panel_brf_start, request.panel_brf_step);
    const Manifest run = read_manifest(request.manifest);
    const std::vector<FileArgument> listed = manifest_input_files(run);
    inputs.insert(inputs.end(), listed.begin(), listed.end());
    check_distinct_files(inputs, outputs);
    return calibrate_manifest(run, read_panel_reflectance(request.panel_reflectance), brf, options);
  }
  if (request.sample.empty() || request.reference.empty()) {
    throw InputError("give `sample` and `reference`, or `manifest` (a run CSV)");
  }
  DatasetReadOptions radiance = request.options_for(std::string());
  radiance.any_units = true;
  CalibrationInput in;
  in.sample = read_dataset(request.sample, radiance);
  in.reference = read_dataset(request.reference, radiance);
  if (!request.dark.empty()) in.dark = read_dataset(request.dark, radiance);
  in.panel_reflectance = read_panel_reflectance(request.panel_reflectance);
  in.panel_brf = read_panel_brf(request.panel_brf, request.panel_brf_start, request.panel_brf_step);
  SpectralDataset out = calibrate(in);
  out.metadata["sample_radiance"] = request.sample;
  out.metadata["reference_radiance"] = request.reference;
  if (!request.dark.empty()) out.metadata["dark"] = request.dark;
  return out;
}

}  // namespace

SpectralDataset calibrate(const CalibrateRequest& request) {
  SpectralDataset out = calibrated(request);
  write_dataset_output(out, request.output, request.format);
  return out;
}

}  // namespace roadbrdf
