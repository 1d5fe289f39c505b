// roadbrdf albedo (FIT.json | MODEL -p ...) [--sun-zenith D|LIST|A:B:STEP] [--diffuse-fraction X|FILE |
//   --atmosphere spectrl2[:aod=...,water=...,ozone=...,pressure=...]] [--spectrum
//   astm-g173-global|astm-g173-direct|FILE]
//   [--fit NAME] [--wavelengths LIST|A:B:STEP] [--illuminant A|D65] [--no-uncertainty] [--json] [-o FILE]
// Black-sky, white-sky and blue-sky albedo per wavelength and solar-weighted (report eqs. 2.19-2.22).
#include <fmt/core.h>
#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "roadbrdf/albedo/report.h"
#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/common.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/progress.h"
#include "roadbrdf/core/range.h"
#include "roadbrdf/spectra/cie.h"

namespace roadbrdf::cli {

namespace {

struct AlbedoArgs {
  std::string model;
  std::vector<std::string> parameters;
  std::vector<std::string> options;
  std::string fit_model;
  std::string sun_zenith = "30";
  std::optional<double> sun_azimuth;
  bool azimuth_mean = false;
  std::string diffuse_fraction;
  std::string atmosphere;
  std::string spectrum;
  std::string wavelengths;
  std::string illuminant;
  double tolerance = 1e-5;
  bool no_uncertainty = false;
  bool as_json = false;
  std::string output;
  bool quiet = false;
};

void run(const AlbedoArgs& a) {
  check_distinct_files({{"MODEL", a.model},
                        {"--diffuse-fraction", a.diffuse_fraction},
                        {"--spectrum", a.spectrum},
                        {"--illuminant", a.illuminant}},
                       {{"-o", a.output}});
  const SpectralModel sm = spectral_model_from_command_line(a.model, a.parameters, a.options, a.fit_model);
  albedo::AlbedoRequest request;
  request.sun_zenith_deg = parse_range_list(a.sun_zenith, "--sun-zenith");
  request.sun_azimuth_deg = a.sun_azimuth;
  request.azimuth_mean = a.azimuth_mean;
  request.diffuse_fraction = a.diffuse_fraction;
  request.atmosphere = a.atmosphere;
  request.spectrum = a.spectrum;
  if (!a.wavelengths.empty())
    request.wavelengths = parse_range_list(a.wavelengths, "--wavelengths", wavelength_rules());
  request.illuminant = a.illuminant;
  request.tolerance = a.tolerance;
  request.uncertainty = !a.no_uncertainty;
  ProgressBar bar("albedo: integrals", stderr, ProgressBar::stderr_style(a.quiet));
  request.progress = bar.callback();
  const nlohmann::json report = albedo::compute_albedo(sm, request);
  bar.finish();
  // Mostly extrapolated or non-physical results are also warnings (the notes are in the output too).
  for (const auto& note : report.at("notes")) {
    const std::string n = note.get<std::string>();
    if (n.rfind("WARNING: mostly", 0) == 0 || n.rfind("WARNING: non-physical", 0) == 0 ||
        n.rfind("WARNING: implausible", 0) == 0) {
      fmt::print(stderr, "roadbrdf: warning: {}\n", n.substr(9));
    }
  }
  albedo::write_albedo_report(report, a.output.empty() ? std::string("-") : a.output, a.as_json);
}

}  // namespace

void register_albedo_command(CLI::App& app) {
  static AlbedoArgs args;
  auto* command = app.add_subcommand(
      "albedo", "Black-sky, white-sky and blue-sky albedo per wavelength and solar-weighted (report eqs. 2.19-2.22)");
  command->add_option("model", args.model, "Fit file (FIT.json) or model name, e.g. oren-nayar+torrance-sparrow")
      ->required();
  add_model_flags(command, args.parameters, args.options);
  add_fit_flag(command, args.fit_model);
  command->add_option("--sun-zenith", args.sun_zenith,
                      "Sun zenith [deg]: D, D1,D2,..., START:STOP:STEP (both ends included) or a mix (default 30)");
  command->add_option("--sun-azimuth", args.sun_azimuth, "Sun azimuth [deg] for anisotropic models (default 0)");
  command->add_flag("--azimuth-mean", args.azimuth_mean, "Anisotropic models: average black-sky over the sun azimuth");
  command->add_option("--diffuse-fraction", args.diffuse_fraction,
                      "Diffuse fraction D for blue-sky: a number in [0, 1] or a CSV wavelength_nm,diffuse_fraction");
  command->add_option("--atmosphere", args.atmosphere,
                      "spectrl2[:aod=0.1,water=1.42,ozone=0.344,pressure=101325,alpha=1.14,ground=0.2,day=81]: "
                      "D(lambda) and the broadband weights from the SPECTRL2 clear-sky model (pressure in Pa, water "
                      "in cm, ozone in atm-cm)");
  command->add_option("--spectrum", args.spectrum,
                      "Broadband weighting: astm-g173-global (default), astm-g173-direct or a CSV wavelength_nm,"
                      "irradiance_W_m2_nm (default with --atmosphere: SPECTRL2 direct + diffuse)");
  command->add_option("--wavelengths", args.wavelengths,
                      "Wavelengths [nm] of a fit file: LIST or START:STOP:STEP (both ends included), increasing");
  command->add_option("--illuminant", args.illuminant,
                      "Also the luminous (V(lambda)-weighted) albedo: A, D65 or a file");
  command->add_option("--tolerance", args.tolerance, "Absolute quadrature tolerance per value (default 1e-5)");
  command->add_flag("--no-uncertainty", args.no_uncertainty,
                    "Skip the standard uncertainties from a fit's parameter covariance (values only)");
  command->add_flag("--json", args.as_json, "JSON output");
  command->add_option("-o,--output", args.output, "Output file (default: standard output)");
  add_quiet_flag(command, args.quiet);
  command->callback([] { run(args); });
}

}  // namespace roadbrdf::cli
