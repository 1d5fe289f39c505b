// roadbrdf mix FORMULATION.json [--data MEASURED.csv] [--method areal|fitted|mastic|hapke|shadowed|all]
//              [--folds K] [--reference FIT.json] [--no-sigma] [--residuals RES.csv] -o MIX.json
// Predicts the BRDF of a road formulation from its components' fits (mixing/mixing.h) and, with
// measured data of the mixed sample, compares the methods with k-fold held-out geometries.
#include <fmt/core.h>

#include <cmath>
#include <iostream>
#include <optional>
#include <sstream>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/dataset_flags.h"
#include "roadbrdf/cli/common.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/fitting/fit_file.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/mixing/mix_file.h"
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
  std::string output;
};

std::string weights_text(const mixing::MixResult& r) {
  std::ostringstream s;
  for (std::size_t k = 0; k < r.end_members.size(); ++k) {
    if (k) s << ' ';
    s << r.end_members[k] << '=' << fmt::format("{:.3f}", r.weights[k]);
  }
  for (const auto& [key, value] : r.settings) {
    if (key == "shadowing") s << " s=" << fmt::format("{:.3g}", value);
  }
  if (std::isfinite(r.weight_distance)) s << fmt::format(" (dist {:.3f}, sum {:.3f})", r.weight_distance, r.weight_sum);
  return s.str();
}

void run(const MixArgs& a) {
  using namespace mixing;
  if (a.output.empty()) throw InputError("give the output file with -o MIX.json");
  std::vector<FileArgument> inputs_read = {{"FORMULATION", a.formulation}, {"--data", a.data}, {"--reference", a.reference}};
  const std::vector<FileArgument> outputs = {{"-o", a.output}, {"--residuals", a.residuals}};
  check_distinct_files(inputs_read, outputs);
  const Formulation formulation = read_formulation(a.formulation);
  if (formulation.mastic) inputs_read.push_back({"mastic.fit of " + a.formulation, formulation.mastic->fit_path});
  for (const auto& c : formulation.components) inputs_read.push_back({"fit of component '" + c.name + "'", c.fit_path});
  check_distinct_files(inputs_read, outputs);
  std::FILE* report = report_stream(a.output);
  const MixInputs inputs = load_mix_inputs(formulation);
  MixSettings settings;
  settings.binder_coverage = a.binder_coverage;
  settings.mastic_area_fraction = a.mastic_fraction;
  settings.per_wavelength = a.per_wavelength;
  settings.sum_to_one = a.sum_to_one;
  settings.use_sigma = !a.no_sigma;
  if (!a.residuals.empty() && a.data.empty()) throw InputError("--residuals needs --data (held-out residuals)");

  std::vector<Method> methods;
  const bool all = a.method == "all";
  if (all) {
    methods = all_methods();
  } else {
    methods = {method_from_string(a.method)};
  }
  std::optional<SpectralDataset> data;
  if (!a.data.empty()) data = read_dataset(a.data, dataset_read_options(a.read));
  std::optional<SpectralModel> reference;
  if (!a.reference.empty()) {
    if (!data) throw InputError("--reference needs --data (the albedo is compared at the data's wavelengths)");
    reference = read_fit_file(a.reference);
  }

  MixFileContent content;
  content.inputs = &inputs;
  content.data_path = a.data;
  content.folds = a.folds;
  for (Method m : methods) {
    if (!data && method_needs_data(m)) {
      if (all) {
        fmt::print(stderr, "roadbrdf: note: method '{}' skipped: it is fitted to a measured mixture (--data)\n",
                   to_string(m));
        continue;
      }
    }
    try {
      if (data) {
        Comparison c = compare_method(inputs, m, settings, *data, a.folds, a.seed, reference ? &*reference : nullptr);
        content.results.push_back(c.result);
        content.comparisons.push_back(std::move(c));
      } else {
        content.results.push_back(mix(inputs, m, settings));
      }
    } catch (const InputError& e) {
      if (!all) throw;
      fmt::print(stderr, "roadbrdf: warning: method '{}' skipped: {}\n", to_string(m), e.what());
    }
  }
  if (content.results.empty()) throw InputError("no mixing method could be applied to " + a.formulation);
  write_mix_file(a.output, content);
  if (!a.residuals.empty()) write_residual_file(a.residuals, *data, content.comparisons);

  fmt::print(report, "formulation {} ({} components, {} end-members)\n", formulation.name, formulation.components.size(),
             inputs.end_members.size());
  if (data) {
    fmt::print(report, "measured mixture {}: {} geometries x {} wavelengths; errors on held-out geometries ({}-fold)\n",
               a.data, data->geometry_count(), data->wavelength_count(), a.folds);
    if (data->has_sigma()) {
      fmt::print(report, "fitted methods {} (sigma from the data); chi2/n: held-out reduced chi^2\n",
                 settings.use_sigma ? "weighted by 1/sigma^2" : "unweighted (--no-sigma)");
    }
    fmt::print(report, "{:<9} {:>12} {:>9} {:>8} {:>12} {:>8} {:>9}  {}\n", "method", "RMSE[sr-1]", "relRMSE", "chi2/n",
               "RMSE(fit)", "albedo", "d_albedo", "weights");
    std::size_t best = 0;
    for (std::size_t i = 0; i < content.comparisons.size(); ++i) {
      const Comparison& c = content.comparisons[i];
      if (c.rmse < content.comparisons[best].rmse) best = i;
      fmt::print(report, "{:<9} {:>12.5g} {:>9.4f} {:>8} {:>12.5g} {:>8.4f} {:>9}  {}\n", to_string(c.method), c.rmse,
                 c.relative_rmse, std::isfinite(c.chi2_reduced) ? fmt::format("{:.4g}", c.chi2_reduced) : std::string("n/a"),
                 c.rmse_in_sample, c.albedo,
                 std::isfinite(c.albedo_difference) ? fmt::format("{:+.4f}", c.albedo_difference) : std::string("n/a"),
                 weights_text(c.result));
    }
    fmt::print(report, "best method for {}: {} (held-out RMSE {:.5g} sr^-1)\n", formulation.name,
               to_string(content.comparisons[best].method), content.comparisons[best].rmse);
  } else {
    fmt::print(report, "{:<9} {:>8}  {}\n", "method", "albedo", "weights");
    for (const auto& r : content.results) {
      const std::vector<double> albedo = mixture_white_sky_albedo(inputs, r, r.model->wavelengths());
      double mean = 0.0;
      for (double x : albedo) mean += x / albedo.size();
      fmt::print(report, "{:<9} {:>8.4f}  {}\n", to_string(r.method), mean, weights_text(r));
    }
  }
  fmt::print(report, "wrote {}\n", a.output);
  if (!a.residuals.empty()) fmt::print(report, "wrote {} (held-out residuals)\n", a.residuals);
}

}  // namespace

void register_mix_command(CLI::App& app) {
  static MixArgs args;
  auto* command = app.add_subcommand(
      "mix", "Predict the BRDF of a road formulation from its components' fits; compare mixing methods with measured data");
  command->add_option("formulation", args.formulation, "Formulation file (JSON, see data/examples/formulations/README.md)")
      ->required();
  command->add_option("--data", args.data, "Measured BRDF of the mixed sample (CSV): compare the methods on it");
  add_dataset_read_flags(command, args.read);
  command->add_option("--method", args.method, "areal | fitted | mastic | hapke | shadowed | all (default all)")
      ->check(CLI::IsMember({"areal", "fitted", "mastic", "hapke", "shadowed", "all"}));
  command->add_option("--folds", args.folds, "Cross-validation folds over geometries (default 5)")
      ->check(CLI::Range(2, 1000));
  command->add_option("--seed", args.seed, "Seed of the geometry shuffle for the folds (default 1)");
  command->add_flag("--per-wavelength", args.per_wavelength, "fitted: one weight set per wavelength (default: one for all)");
  command->add_flag("--sum-to-one", args.sum_to_one, "fitted, shadowed: constrain the weights to sum to one");
  command->add_option("--binder-coverage", args.binder_coverage,
                      "areal: fraction of the surface covered by binder, overriding the formulation")
      ->check(CLI::Range(0.0, 1.0));
  command->add_option("--mastic-fraction", args.mastic_fraction,
                      "mastic: area fraction of the mastic, overriding the formulation")
      ->check(CLI::Range(0.0, 1.0));
  command->add_flag("--no-sigma", args.no_sigma,
                    "fitted, shadowed: ignore the data's sigma (default: weight residuals by 1/sigma^2 when given)");
  command->add_option("--residuals", args.residuals,
                      "With --data: write the held-out residuals per method, geometry and wavelength (CSV, "
                      "see docs/mixing.md)");
  command->add_option("--reference", args.reference,
                      "Fit file of the measured mixture: the albedo difference column compares with it");
  command->add_option("-o,--output", args.output, "Output MIX.json (format: src/roadbrdf/mixing/mix_file.h)")->required();
  command->callback([] { run(args); });
}

}  // namespace roadbrdf::cli
