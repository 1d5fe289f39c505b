// roadbrdf albedo (FIT.json | MIX.json | MODEL -p ...) [--sun-zenith D|LIST|A:B:STEP] [--diffuse-fraction X|FILE |
//   --atmosphere spectrl2[:aod=...,water=...,ozone=...,pressure=...]] [--spectrum
//   astm-g173-global|astm-g173-direct|FILE]
//   [--fit NAME] [--wavelengths LIST|A:B:STEP] [--illuminant A|D65] [--no-uncertainty] [--json] [-o FILE]
// Black-sky, white-sky and blue-sky albedo per wavelength and solar-weighted (report eqs. 2.19-2.22).
// Made by the request contract (cli/request_options.h; the request's table is in albedo/albedo_request.cpp).
#include "roadbrdf/albedo/report.h"
#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/request_options.h"
#include "roadbrdf/core/progress.h"

namespace roadbrdf::cli {

namespace {

struct AlbedoArgs {
  albedo::AlbedoRequest request;
  bool as_json = false;
  std::string output;
  bool quiet = false;
};

void run(AlbedoArgs& a) {
  albedo::AlbedoResult result;
  run_request<albedo::AlbedoRequest>([&] {
    std::vector<FileArgument> inputs, outputs{{"-o", a.output}};
    file_arguments(a.request, albedo::AlbedoRequest::fields(), inputs, outputs);
    check_distinct_files(inputs, outputs);
    ProgressBar bar("albedo: integrals", stderr, ProgressBar::stderr_style(a.quiet));
    a.request.progress = bar.callback();
    result = albedo::albedo(a.request);
    bar.finish();
  });
  print_diagnostics<albedo::AlbedoRequest>(result.diagnostics);
  albedo::write_albedo_report(result.report, a.output.empty() ? std::string("-") : a.output, a.as_json);
}

}  // namespace

void register_albedo_command(CLI::App& app) {
  static AlbedoArgs args;
  auto* command = app.add_subcommand(
      "albedo", "Black-sky, white-sky and blue-sky albedo per wavelength and solar-weighted (report eqs. 2.19-2.22)");
  add_request_options(command, args.request);
  refuse_fit_model_flag(command);
  command->add_flag("--json", args.as_json, "JSON output");
  command->add_option("-o,--output", args.output, "Output file (default: standard output)");
  add_quiet_flag(command, args.quiet);
  command->callback([] { run(args); });
}

}  // namespace roadbrdf::cli
