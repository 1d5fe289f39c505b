// roadbrdf calibrate SAMPLE.csv --reference REF.csv [--dark DARK.csv] --panel-reflectance RHO.txt
//                    [--panel-brf BRF.txt] -o DATA.csv
// roadbrdf calibrate --manifest RUN.csv --panel-reflectance RHO.txt -o DATA.csv   (cli/instruments.h)
// f = (L_s - L_dark)/(L_ref - L_dark) * rho_ref(lambda)/pi (io/calibration.h).
#include <fmt/core.h>

#include <iostream>
#include <optional>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/common.h"
#include "roadbrdf/cli/dataset_flags.h"
#include "roadbrdf/cli/instruments.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/io/calibration.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/spectra/spectrum_file.h"

namespace roadbrdf::cli {

namespace {

struct CalibrateArgs {
  DatasetReadFlags read;
  std::string sample, reference, dark, panel, panel_brf;
  std::optional<double> brf_start, brf_step;
  std::string format = "wide";
  std::string output;
  std::string manifest;
  InstrumentArgs instrument;
};

void run(const CalibrateArgs& a) {
  const std::vector<FileArgument> inputs = {{"SAMPLE", a.sample},         {"--reference", a.reference},
                                            {"--dark", a.dark},           {"--panel-reflectance", a.panel},
                                            {"--panel-brf", a.panel_brf}, {"--manifest", a.manifest}};
  const std::vector<FileArgument> outputs = {{"-o", a.output}};
  check_distinct_files(inputs, outputs);
  if (!a.manifest.empty()) {
    if (!a.sample.empty() || !a.reference.empty() || !a.dark.empty()) {
      throw InputError("--manifest gives the sample, white reference and dark files: no SAMPLE, --reference or --dark");
    }
    SpectralDataset out = calibrate_manifest_from_command_line(a.manifest, a.panel, a.panel_brf, a.brf_start,
                                                               a.brf_step, a.instrument, inputs, outputs);
    write_dataset_output(out, a.output, a.format);
    return;
  }
  if (a.sample.empty() || a.reference.empty()) throw InputError("give SAMPLE and --reference, or --manifest RUN.csv");
  DatasetReadOptions radiance = dataset_read_options(a.read);
  radiance.any_units = true;
  CalibrationInput in;
  in.sample = read_dataset(a.sample, radiance);
  in.reference = read_dataset(a.reference, radiance);
  if (!a.dark.empty()) in.dark = read_dataset(a.dark, radiance);
  in.panel_reflectance = read_panel_reflectance(a.panel);
  in.panel_brf = read_panel_brf(a.panel_brf, a.brf_start, a.brf_step);
  SpectralDataset out = calibrate(in);
  out.metadata["sample_radiance"] = a.sample;
  out.metadata["reference_radiance"] = a.reference;
  if (!a.dark.empty()) out.metadata["dark"] = a.dark;
  write_dataset_output(out, a.output, a.format);
}

}  // namespace

void register_calibrate_command(CLI::App& app) {
  static CalibrateArgs args;
  auto* c = app.add_subcommand(
      "calibrate", "BRDF from sample and reference-panel radiances: f = (L_s - L_dark)/(L_ref - L_dark) x rho_ref/pi");
  c->add_option("sample", args.sample, "Sample radiances, dataset CSV (any units; sigma_<nm> columns optional)");
  c->add_option("--reference", args.reference,
                "Reference-panel radiances: same geometries as the sample, or a single row used for every geometry");
  c->add_option("--manifest", args.manifest,
                "Instrument run: CSV of file,role (sample|white|dark) and angles, mapping .asd/.sed/.sig files to "
                "geometries (replaces SAMPLE, --reference and --dark; docs/data.md)");
  add_instrument_flags(c, args.instrument, false);
  add_dataset_read_flags(c, args.read);
  c->add_option("--dark", args.dark, "Dark signal: same geometries, or a single row (default: none)");
  c->add_option("--panel-reflectance", args.panel,
                "Calibrated panel reflectance rho_ref: wavelength [nm], value [, sigma] (e.g. Spectralon_Num4.txt)")
      ->required();
  c->add_option("--panel-brf", args.panel_brf,
                "Measured BRF of the panel at the measurement geometry (replaces rho_ref: non-Lambertian correction)");
  c->add_option("--panel-brf-start", args.brf_start, "First wavelength of a one-column --panel-brf file [nm]");
  c->add_option("--panel-brf-step", args.brf_step, "Wavelength step of a one-column --panel-brf file [nm]");
  c->add_option("--format", args.format, "Output format: " + names_text<DatasetFormat>() + " (default wide)");
  c->add_option("-o,--output", args.output, "Output BRDF dataset CSV (default: standard output)");
  c->callback([] { run(args); });
}

}  // namespace roadbrdf::cli
