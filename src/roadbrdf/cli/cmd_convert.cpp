// roadbrdf convert INPUT... [--from SOURCE] [--to wide|long] -o OUT.csv
// (several dataset CSV files: runs of one sample combined into one dataset, io/dataset_runs.h)
// (instrument files and manifests: cli/instruments.h)
#include <fmt/core.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/common.h"
#include "roadbrdf/cli/dataset_flags.h"
#include "roadbrdf/cli/instruments.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/io/alta.h"
#include "roadbrdf/io/curet.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/dataset_runs.h"

namespace roadbrdf::cli {

namespace {

struct ConvertArgs {
  std::vector<std::string> inputs;
  std::string input;
  std::string from = "auto";
  std::string to = "wide";
  std::string curet_table;
  int sample = -1;
  std::optional<double> wavelength;
  std::string alta_output;
  bool exclude_grazing = false;
  DatasetReadFlags read;
  std::string convention;
  std::string output;
  InstrumentArgs instrument;
};

void run(ConvertArgs& a) {
  a.input = a.inputs.front();
  std::vector<FileArgument> inputs = {{"--curet-table", a.curet_table}};
  for (const std::string& path : a.inputs) inputs.push_back({"INPUT", path});
  const std::vector<FileArgument> outputs = {{"-o", a.output}};
  check_distinct_files(inputs, outputs);
  const ConvertSource from = parse_name<ConvertSource>(a.from, "from");
  SpectralDataset d;
  const bool runs = from == ConvertSource::kAuto || from == ConvertSource::kWide || from == ConvertSource::kLong;
  if (a.inputs.size() > 1 && !(runs && !is_instrument_input(from, a.input))) {
    throw InputError("several INPUT files combine only as dataset CSV files (wide or long)");
  }
  if (is_instrument_input(from, a.input)) {
    d = convert_instrument_input(from, a.input, a.instrument, inputs, outputs);
  } else if (from == ConvertSource::kCuret) {
    if (a.sample < 0) {
      std::string list;
      for (int s : curet_sample_numbers(a.input)) list += fmt::format("{}{}", list.empty() ? "" : " ", s);
      throw InputError("give --sample N for a CUReT file (samples present: " + list + ")");
    }
    const std::string table =
        a.curet_table.empty() ? (std::filesystem::path(a.input).parent_path() / "table.txt").string() : a.curet_table;
    check_distinct_files({{"INPUT", a.input}, {"--curet-table", table}}, {{"-o", a.output}});
    CuretReadOptions o;
    if (a.wavelength) {
      if (!(std::isfinite(*a.wavelength) && *a.wavelength > 0.0)) {
        throw InputError(fmt::format("--wavelength {} nm: must be finite and > 0", *a.wavelength));
      }
      o.nominal_wavelength_nm = *a.wavelength;
    }
    d = read_curet(a.input, table, a.sample, o);
  } else if (from == ConvertSource::kAlta) {
    AltaReadOptions o;
    o.wavelength_nm = a.wavelength.value_or(0.0);
    o.assumed_output = a.alta_output;
    o.exclude_grazing = a.exclude_grazing;
    o.average_duplicates = a.read.average_duplicates;
    d = read_alta(a.input, o);
  } else {  // auto (not an instrument file), wide or long: the CSV reader tells wide from long
    if (!a.instrument.quantity.empty()) a.read.quantity = a.instrument.quantity;
    dataset_read_options(a.read, a.input, a.inputs);  // the fields' errors spelt as flags
    d = read_dataset_runs(a.inputs, a.read);
  }
  if (!a.convention.empty()) d.convention = parse_name<AngleConvention>(a.convention, "convention");
  write_dataset_output(d, a.output, a.to, "to");
}

}  // namespace

void register_convert_command(CLI::App& app) {
  static ConvertArgs args;
  auto* c = app.add_subcommand("convert",
                               "Convert a dataset between wide/long CSV, and from CUReT, ALTA, instrument (.asd, .sed, "
                               ".sig), manifest and USGS splib07a files");
  c->add_option("input", args.inputs,
                "Input file (for CUReT: abrdf.dat); several dataset CSV files (runs of one sample) are combined")
      ->required();
  c->add_option("--from", args.from, "Input format: " + described_names_text<ConvertSource>());
  c->add_option("--to", args.to, "Output format: " + names_text<DatasetFormat>() + " (default wide)");
  c->add_option("--curet-table", args.curet_table, "CUReT geometry table (default: table.txt next to the input)");
  c->add_option("--sample", args.sample, "CUReT sample number (first column of abrdf.dat)");
  c->add_option("--wavelength", args.wavelength,
                "Wavelength [nm] to store single-channel data at (ALTA: required; CUReT: default 550)");
  c->add_option("--alta-output", args.alta_output,
                "ALTA output unit when the file lacks #PARAM_OUT: " + described_names_text<AltaOutput>());
  c->add_flag("--exclude-grazing", args.exclude_grazing,
              "ALTA BRDF x cos(theta_v): leave out (and report) rows at grazing view, which cannot be converted");
  add_dataset_read_flags(c, args.read, false);
  c->add_option("--convention", args.convention,
                "Angle columns of the output: " + described_names_text<AngleConvention>() + " (default: as read)");
  add_instrument_flags(c, args.instrument);
  c->add_option("-o,--output", args.output, "Output dataset CSV (default: standard output)");
  c->callback([] { run(args); });
}

}  // namespace roadbrdf::cli
