// roadbrdf mix FORMULATION.json [--data MEASURED.csv] [--method METHOD|all]
//              [--folds K] [--reference FIT.json] [--no-sigma-weights] [--residuals RES.csv]
//              [--cross-sections CAL.json] [--uncertainty] -o MIX.json
// Predicts the BRDF of a road formulation from its components' fits (mixing/mixing.h) and, with
// measured data of the mixed sample, compares the methods with k-fold held-out geometries. The
// options are MixRequest's table (cli/request_options.h).
#include <fmt/core.h>

#include <cstdio>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/common.h"
#include "roadbrdf/cli/request_options.h"
#include "roadbrdf/core/progress.h"
#include "roadbrdf/mixing/mix_request.h"

namespace roadbrdf::cli {

namespace {

void run(mixing::MixRequest request, bool quiet) {
  ProgressBar bar("mix: mixes (methods x folds)", stderr, ProgressBar::stderr_style(quiet));
  request.progress = bar.callback();
  const mixing::MixRun run = mixing::run_mix(request);
  bar.finish();
  for (const auto& note : run.notes) {
    fmt::print(stderr, "roadbrdf: warning: {}\n", with_flags<mixing::MixRequest>(note));
  }
  mixing::write_mix_outputs(run);
  std::FILE* report = report_stream(request.output);
  fmt::print(report, "{}", run.table());
  fmt::print(report, "wrote {}\n", request.output);
  if (!request.residuals.empty()) fmt::print(report, "wrote {} (held-out residuals)\n", request.residuals);
}

}  // namespace

void register_mix_command(CLI::App& app) {
  static mixing::MixRequest request;
  static bool quiet = false;
  auto* command = app.add_subcommand(
      "mix",
      "Predict the BRDF of a road formulation from its components' fits; compare mixing methods with measured data");
  add_request_options(command, request);
  command->get_option("--output")->required();  // Python need not write a file; the command writes one
  // The sigma switch under its shorter name, hidden: the help shows the name `fit` also uses.
  command
      ->add_flag_callback(
          "--no-sigma", [] { request.use_sigma = false; }, "")
      ->group("");
  add_quiet_flag(command, quiet);
  command->callback([] { run_request<mixing::MixRequest>([] { run(request, quiet); }); });
}

}  // namespace roadbrdf::cli
