// roadbrdf simulate MODEL_OR_FIT --grid GRID.csv --wavelengths A:B:STEP [--spectral NAME=FILE] [--noise ...]
//                   [--seed S] -o DATA.csv
// Virtual gonioreflectometer (io/simulate.h).
#include <fmt/core.h>

#include <iostream>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/common.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/geometry_file.h"
#include "roadbrdf/io/resample.h"
#include "roadbrdf/io/simulate.h"
#include "roadbrdf/spectra/spectrum_file.h"

namespace roadbrdf::cli {

namespace {

struct SimulateArgs {
  std::string model;
  std::vector<std::string> parameters, options, spectral, metadata;
  std::string fit_model;
  std::string grid;
  std::string wavelengths;
  std::string noise = "none";
  std::uint64_t seed = 1;
  bool no_sigma = false;
  int digits = 0;
  std::string format = "wide";
  std::string output;
};

void run(const SimulateArgs& a) {
  std::vector<FileArgument> inputs = {{"MODEL", a.model}, {"--grid", a.grid}};
  for (const auto& item : a.spectral) {
    const auto eq = item.find('=');
    if (eq != std::string::npos) inputs.push_back({"--spectral", item.substr(eq + 1)});
  }
  check_distinct_files(inputs, {{"-o", a.output}});
  const SpectralModel model = spectral_model_from_command_line(a.model, a.parameters, a.options, a.fit_model);
  const GeometryTable grid = read_geometry_file(a.grid);
  SimulationInput in;
  in.model = &model;
  in.geometries = grid.geometries;
  in.convention = grid.convention;
  if (!a.wavelengths.empty()) {
    in.wavelengths = parse_range_list(a.wavelengths, "--wavelengths", wavelength_rules());
  } else if (model.is_spectral()) {
    in.wavelengths = model.wavelengths();
  } else {
    throw InputError("give --wavelengths START:STOP:STEP [nm] (the model is not spectral)");
  }
  for (const auto& item : a.spectral) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0) throw InputError("--spectral expects NAME=FILE, got '" + item + "'");
    const std::string name = item.substr(0, eq);
    if (in.spectral_parameters.count(name)) throw InputError("--spectral " + name + " is given twice");
    if (std::find_if(a.parameters.begin(), a.parameters.end(),
                     [&](const std::string& p) { return p.rfind(name + "=", 0) == 0; }) != a.parameters.end()) {
      throw InputError("parameter " + name + " is given both by -p and by --spectral");
    }
    in.spectral_parameters[name] = spectra::read_spectrum(item.substr(eq + 1));
  }
  in.noise = parse_noise_model(a.noise);
  in.seed = a.seed;
  in.write_sigma = !a.no_sigma;
  if (a.digits < 0 || a.digits > 17) throw InputError("--digits must be in [0, 17]");
  in.significant_digits = a.digits;
  SpectralDataset d = simulate_dataset(in);
  d.metadata["grid"] = a.grid;
  for (const auto& [k, v] : parse_option_assignments(a.metadata, "--metadata")) d.metadata[k] = v;
  write_dataset_output(d, a.output, a.format);
}

}  // namespace

void register_simulate_command(CLI::App& app) {
  static SimulateArgs args;
  auto* c = app.add_subcommand(
      "simulate", "Virtual gonioreflectometer: sample a model or a fit on an instrument grid, with reproducible noise");
  c->add_option("model", args.model, "Model name (with -p/--option) or fit file FIT.json")->required();
  add_model_flags(c, args.parameters, args.options);
  add_fit_flag(c, args.fit_model);
  c->add_option("--grid", args.grid, "Geometry grid CSV: theta_i,phi_i,theta_r,phi_r or gamma,alpha,beta,delta [deg]")
      ->required();
  c->add_option("--wavelengths", args.wavelengths,
                "Wavelengths [nm]: START:STOP:STEP (both ends included), a list or a mix, increasing "
                "(default: the fit's wavelengths)");
  c->add_option("--spectral", args.spectral,
                "Parameter given as a spectrum NAME=FILE (wavelength [nm], value; linear interpolation, no "
                "extrapolation), e.g. albedo=bitumen-albedo.csv; repeatable")
      ->allow_extra_args(false);
  c->add_option("--noise", args.noise,
                "Noise model: none, or relative=R,absolute=A[sr^-1],edge=E,edge-width=W[nm],water=F,"
                "detector-min=NM,detector-max=NM (sigma = sqrt((R f)^2 + A^2) x spectral shape)");
  c->add_option("--seed", args.seed, "Seed of the noise (same seed, same data)");
  c->add_option("--digits", args.digits,
                "Round values to N significant digits as an instrument file would (0 = full precision; sigma to 2)");
  c->add_flag("--no-sigma", args.no_sigma, "Do not write the noise standard deviation as sigma_<nm> columns");
  c->add_option("--metadata", args.metadata, "Extra metadata KEY=VALUE written as '# key: value' (repeatable)")
      ->allow_extra_args(false);
  c->add_option("--format", args.format, "Output format: " + names_text<DatasetFormat>() + " (default wide)");
  c->add_option("-o,--output", args.output, "Output dataset CSV (default: standard output)");
  c->callback([] { run(args); });
}

}  // namespace roadbrdf::cli
