// roadbrdf mix FORMULATION.json [--data MEASURED.csv] [--method METHOD|all]
//              [--folds K] [--reference FIT.json] [--no-sigma-weights] [--residuals RES.csv]
//              [--cross-sections CAL.json] [--uncertainty] -o MIX.json
// Predicts the BRDF of a road formulation from its components' fits (mixing/mixing.h) and, with
// measured data of the mixed sample, compares the methods with k-fold held-out geometries.
#include <fmt/core.h>

#include <cmath>
#include <iostream>
#include <optional>
#include <sstream>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/common.h"
#include "roadbrdf/cli/dataset_flags.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/progress.h"
#include "roadbrdf/fitting/fit_file.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/mixing/mix_file.h"
#include "roadbrdf/mixing/mix_request.h"
#include "roadbrdf/mixing/mixing.h"
#include "roadbrdf/mixing/residual_file.h"
#include "roadbrdf/models/spectral_model.h"

namespace roadbrdf::cli {

namespace {

struct MixArgs {
  std::string formulation;
  std::string data;
  DatasetReadFlags read;
  std::string method = "all";
  int folds = 5;
  unsigned seed = 1;
  bool per_wavelength = false;
  bool sum_to_one = false;
  bool no_sigma = false;
  std::string residuals;
  std::optional<double> binder_coverage;
  std::optional<double> mastic_fraction;
  std::string reference;
  std::string cross_sections;
  std::string output;
  bool uncertainty = false;
  bool quiet = false;
};

void run(const MixArgs& a) {
  using namespace mixing;
  if (a.output.empty()) throw InputError("give the output file with -o MIX.json");
  MixRequest request;
  request.formulation = a.formulation;
  request.data = a.data;
  request.data_read = dataset_read_options(a.read);
  request.method = a.method;
  request.folds = a.folds;
  request.seed = a.seed;
  request.per_wavelength = a.per_wavelength;
  request.sum_to_one = a.sum_to_one;
  request.use_sigma = !a.no_sigma;
  request.binder_coverage = a.binder_coverage;
  request.mastic_fraction = a.mastic_fraction;
  request.reference = a.reference;
  request.cross_sections = a.cross_sections;
  request.uncertainty = a.uncertainty;
  request.residuals = !a.residuals.empty();
  ProgressBar bar("mix: mixes (methods x folds)", stderr, ProgressBar::stderr_style(a.quiet));
  request.progress = bar.callback();
  const MixRun run = run_mix(request, {{"-o", a.output}, {"--residuals", a.residuals}}, [](const std::string& field) {
    return field == "formulation" ? std::string("FORMULATION") : flag_for_field(field);
  });
  bar.finish();
  for (const auto& note : run.notes) fmt::print(stderr, "roadbrdf: warning: {}\n", name_flags(note));
  write_mix_file(a.output, run.content);
  if (!a.residuals.empty()) write_residual_file(a.residuals, *run.data, run.content.comparisons);
  std::FILE* report = report_stream(a.output);
  fmt::print(report, "{}", run.table());
  fmt::print(report, "wrote {}\n", a.output);
  if (!a.residuals.empty()) fmt::print(report, "wrote {} (held-out residuals)\n", a.residuals);
}

}  // namespace

void register_mix_command(CLI::App& app) {
  static MixArgs args;
  auto* command = app.add_subcommand(
      "mix",
      "Predict the BRDF of a road formulation from its components' fits; compare mixing methods with measured data");
  command
      ->add_option("formulation", args.formulation, "Formulation file (JSON, see data/examples/formulations/README.md)")
      ->required();
  command->add_option("--data", args.data, "Measured BRDF of the mixed sample (CSV): compare the methods on it");
  add_dataset_read_flags(command, args.read);
  command->add_option("--method", args.method, "Mixing method: " + names_text<mixing::Method>() + ", or all (default)");
  command->add_option("--folds", args.folds, "Cross-validation folds over geometries (default 5)");
  command->add_option("--seed", args.seed, "Seed of the geometry shuffle for the folds (default 1)");
  command->add_flag("--per-wavelength", args.per_wavelength,
                    "fitted: one weight set per wavelength (default: one for all)");
  command->add_flag("--uncertainty", args.uncertainty,
                    "areal, mastic, hapke: carry the components' fit covariances into MIX.json (albedo and rtable "
                    "of it then give uncertainties; the albedo becomes much slower)");
  command->add_flag("--sum-to-one", args.sum_to_one, "fitted, shadowed: constrain the weights to sum to one");
  command->add_option("--binder-coverage", args.binder_coverage,
                      "areal: fraction of the surface covered by binder, overriding the formulation");
  command->add_option("--mastic-fraction", args.mastic_fraction,
                      "mastic: area fraction of the mastic, overriding the formulation");
  command->add_flag("--no-sigma-weights", args.no_sigma,
                    "fitted, shadowed: ignore the data's sigma (default: weight residuals by 1/sigma^2 when given)");
  // The same flag under its shorter name, hidden: the help shows the name `fit` also uses.
  command->add_flag("--no-sigma", args.no_sigma, "")->group("");
  command->add_option("--residuals", args.residuals,
                      "With --data: write the held-out residuals per method, geometry and wavelength (CSV, "
                      "see docs/mixing.md)");
  command->add_option("--reference", args.reference,
                      "Fit file of the measured mixture: the albedo difference column compares with it");
  command->add_option("--cross-sections", args.cross_sections,
                      "hapke: calibrated cross-section factors per end-member (file of `roadbrdf mix-calibrate`)");
  command->add_option("-o,--output", args.output, "Output MIX.json (format: src/roadbrdf/mixing/mix_file.h)")
      ->required();
  add_quiet_flag(command, args.quiet);
  command->callback([] { run(args); });
}

}  // namespace roadbrdf::cli
