// roadbrdf resample DATA.csv --wavelengths 400:1000:10 [--drop A:B]... [--drop-noisy] -o OUT.csv
#include <fmt/core.h>

#include <iostream>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/common.h"
#include "roadbrdf/cli/dataset_flags.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/range.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/quality.h"
#include "roadbrdf/io/resample.h"

namespace roadbrdf::cli {

namespace {

struct ResampleArgs {
  std::string data;
  DatasetReadFlags read;
  std::string wavelengths;
  std::vector<std::string> drop;
  bool drop_noisy = false;
  double snr_threshold = 20.0;
  std::string format = "wide";
  std::string output;
};

void run(const ResampleArgs& a) {
  check_distinct_files({{"DATA", a.data}}, {{"-o", a.output}});
  const SpectralDataset d = read_dataset(a.data, dataset_read_options(a.read));
  const WavelengthBands bands = bands_from_edges(parse_range_list(a.wavelengths, "--wavelengths", wavelength_rules()));
  std::vector<std::pair<double, double>> drop;
  for (const auto& item : a.drop) {
    const auto [lo, hi] = parse_interval(item, "--drop");
    if (!(lo > 0.0)) throw FieldError("--drop", "'" + item + "': need 0 < FROM <= TO [nm]");
    drop.emplace_back(lo, hi);
  }
  std::string noisy_text;
  if (a.drop_noisy) {
    QualityOptions o;
    o.snr_threshold = a.snr_threshold;
    const QualityReport r = check_dataset(d, o);
    for (const auto& b : r.noisy_bands) {
      drop.emplace_back(b.lower_nm, b.upper_nm);
      noisy_text += fmt::format("{}{}-{}", noisy_text.empty() ? "" : " ", b.lower_nm, b.upper_nm);
    }
  }
  SpectralDataset out = resample_dataset(d, bands, drop);
  if (!noisy_text.empty()) out.metadata["noisy_bands_nm"] = noisy_text;
  write_dataset_output(out, a.output, a.format);
}

}  // namespace

void register_resample_command(CLI::App& app) {
  static ResampleArgs args;
  auto* c = app.add_subcommand("resample",
                               "Band-average a dataset onto new wavelength intervals (not point picks); drop bands");
  c->add_option("data", args.data, "Dataset CSV (wide or long)")->required();
  add_dataset_read_flags(c, args.read);
  c->add_option("--wavelengths", args.wavelengths,
                "Band edges START:STOP:STEP [nm]: bands [START, START+STEP], ... reported at their centres")
      ->required();
  c->add_option("--drop", args.drop, "Leave out the bands overlapping FROM:TO [nm] (repeatable)")
      ->allow_extra_args(false);
  c->add_flag("--drop-noisy", args.drop_noisy, "Leave out the bands overlapping the noisy bands found by `check`");
  c->add_option("--snr-threshold", args.snr_threshold, "Signal-to-noise threshold of --drop-noisy");
  c->add_option("--format", args.format, "Output format: " + names_text<DatasetFormat>() + " (default wide)");
  c->add_option("-o,--output", args.output, "Output dataset CSV (default: standard output)");
  c->callback([] { run(args); });
}

}  // namespace roadbrdf::cli
