// roadbrdf fit DATA.csv --model M [--model M2 ...] [...] -o FIT.json
// Fits each model to every wavelength of a measured spectral BRDF (fitting/fit.h), prints a
// ranking table and writes the fit file (fitting/fit_file.h), which every command accepts as a model.
#include <fmt/core.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <set>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/common.h"
#include "roadbrdf/cli/dataset_flags.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/progress.h"
#include "roadbrdf/core/range.h"
#include "roadbrdf/fitting/fit.h"
#include "roadbrdf/fitting/fit_file.h"
#include "roadbrdf/fitting/fit_request.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf::cli {

namespace {

struct FitArgs {
  std::string data;
  DatasetReadFlags read;
  std::vector<std::string> models;
  std::vector<std::string> options;
  std::vector<std::string> shared;
  std::vector<std::string> fixed;
  std::vector<std::string> start;
  std::vector<std::string> bounds;
  std::string loss = "plain";
  std::string robust = "none";
  bool solid_angle = false;
  bool no_sigma = false;
  int multistart = 1;
  unsigned seed = 1;
  std::string wavelengths;
  std::vector<std::string> bands;
  std::string where;
  std::vector<std::string> group_by;
  int threads = 1;
  int max_iterations = 200;
  bool no_covariance = false;
  std::string joint_solver = "dense-schur";
  bool no_warm_start = false;
  bool no_amplitude_solve = false;
  std::string residuals;
  std::string output;
  bool quiet = false;
};

// "NAME=LOWER:UPPER" items of --bound.
std::map<std::string, std::pair<double, double>> parse_bounds(const std::vector<std::string>& items) {
  std::map<std::string, std::pair<double, double>> out;
  for (const auto& [name, text] : parse_option_assignments(items, "--bound")) {
    out[name] = parse_interval(text, "--bound " + name);
  }
  return out;
}

void run(const FitArgs& a) {
  if (a.output.empty()) throw InputError("give the output fit file with -o FIT.json");
  check_distinct_files({{"DATA", a.data}}, {{"-o", a.output}, {"--residuals", a.residuals}});
  FitRequest request;
  request.models = a.models;
  request.options = parse_option_assignments(a.options, "--option");
  request.fixed = parse_numeric_assignments(a.fixed, "--fix");
  request.start = parse_numeric_assignments(a.start, "--start");
  request.bounds = parse_bounds(a.bounds);
  request.shared = split_commas(a.shared);
  if (!a.wavelengths.empty()) request.wavelengths = parse_range_list(a.wavelengths, "--wavelengths");
  for (const auto& band : a.bands) request.bands.push_back(parse_interval(band, "--band"));
  request.where = a.where;
  request.group_by = split_commas(a.group_by);
  request.loss = a.loss;
  request.robust = a.robust;
  request.solid_angle_weights = a.solid_angle;
  request.use_sigma = !a.no_sigma;
  request.multistart = a.multistart;
  request.seed = a.seed;
  request.threads = a.threads;
  request.max_iterations = a.max_iterations;
  request.covariance = !a.no_covariance;
  request.warm_start = !a.no_warm_start;
  request.joint_solver = a.joint_solver;
  request.solve_amplitudes = !a.no_amplitude_solve;
  request.validate();  // before reading the data: a misspelt name fails at once

  const SpectralDataset data = read_dataset(a.data, dataset_read_options(a.read));
  // One bar per model; the models are fitted one after the other, so a new bar ends the previous one.
  // core/progress.h: on standard error, a bar on a terminal, a heartbeat line in a log; none with --quiet.
  std::unique_ptr<ProgressBar> bar;
  const ProgressStyle show = ProgressBar::stderr_style(a.quiet);
  const FitSummary summary = run_fit(request, data, [&bar, show](const std::string& label) {
    bar.reset();  // ends the previous model's line
    bar = std::make_unique<ProgressBar>(label, stderr, show);
    return [current = bar.get()](std::size_t done, std::size_t total) { current->update(done, total); };
  });
  bar.reset();
  std::FILE* report = report_stream(a.output);
  for (const auto& note : summary.notes) fmt::print(stderr, "roadbrdf: note: {}\n", name_flags(note));
  fmt::print(report, "{}", summary.table());
  for (const auto& w : summary.warnings(a.output)) fmt::print(stderr, "roadbrdf: warning: {}\n", name_flags(w));
  write_fit_file(a.output, summary.fits, summary.notes);
  if (!a.residuals.empty()) {
    std::vector<const Model*> ptrs;
    for (const auto& m : summary.models) ptrs.push_back(m.get());
    AtomicFile out(a.residuals);
    const SpectralDataset fitted = fitted_spectra(request, data);  // its notes are printed above
    write_residuals(out.stream(), fitted, ptrs, summary.fits, request.where);
    out.commit();
  }
}

}  // namespace

void register_fit_command(CLI::App& app) {
  static FitArgs args;
  auto* c = app.add_subcommand(
      "fit",
      "Fit models to a measured spectral BRDF (per wavelength, or jointly with --shared); rank them by BIC; "
      "write a fit file usable as a model");
  c->add_option("data", args.data, "Dataset CSV (wide or long, BRDF in sr^-1, angles in degrees)")->required();
  add_dataset_read_flags(c, args.read);
  c->add_option("-m,--model", args.models, "Model to fit (repeatable), e.g. oren-nayar or oren-nayar+torrance-sparrow")
      ->allow_extra_args(false);
  c->add_option("--option", args.options, "Model option NAME=VALUE (repeatable), for every model declaring it")
      ->allow_extra_args(false);
  c->add_option("--shared", args.shared,
                "Parameters shared across wavelengths, comma-separated (joint spectral fit); 'auto' = the "
                "parameters declared non-spectral")
      ->allow_extra_args(false);
  c->add_option("--fix", args.fixed, "Hold a parameter NAME=VALUE at every wavelength (repeatable)")
      ->allow_extra_args(false);
  c->add_option("--start", args.start, "Starting value NAME=VALUE (repeatable); model defaults otherwise")
      ->allow_extra_args(false);
  c->add_option("--bound,--bounds", args.bounds,
                "Bounds NAME=LOWER:UPPER replacing a parameter's default fitting range, narrower or wider inside its "
                "physical range (`roadbrdf models --json`: physical_bounds) (repeatable); a default start outside "
                "them moves to their middle")
      ->allow_extra_args(false);
  c->add_option("--loss", args.loss, "Residual: " + described_names_text<FitLoss>())->capture_default_str();
  c->add_option("--robust", args.robust,
                "Robust loss, none or NAME:SCALE (SCALE in residual units): " + described_names_text<RobustLoss>())
      ->capture_default_str();
  c->add_flag("--solid-angle-weights", args.solid_angle,
              "Weight each geometry by its solid-angle cell (nearest-neighbour estimate, fitting/fit.h)");
  c->add_flag("--no-sigma-weights", args.no_sigma, "Ignore the dataset's uncertainties (default: weights 1/sigma^2)");
  c->add_option("--multistart", args.multistart,
                "Starting points per fit (1 to 10000): the start, then a Latin hypercube over the nonlinear parameters")
      ->capture_default_str();
  c->add_option("--seed", args.seed, "Seed of the multi-start points")->capture_default_str();
  c->add_option("--wavelengths", args.wavelengths, "Wavelengths to fit: START:STOP:STEP or a list, nm");
  c->add_option("--band", args.bands,
                "Fit the mean of the measured spectrum over LOWER:UPPER nm, at the band's centre (repeatable; "
                "e.g. --band 590:610 on a 20 nm grid; not with --wavelengths)")
      ->allow_extra_args(false);
  c->add_option("--where", args.where,
                "Fit only the geometries where every comparison holds: COLUMN OP DEGREES joined by ',' or 'and', "
                "e.g. 'theta_r<=70'; OP < <= > >= = !=; columns theta_i phi_i theta_r phi_r gamma alpha beta delta");
  c->add_option("--group-by", args.group_by,
                "Fit each group of geometries with equal angles separately, e.g. theta_i (one fit per incidence) "
                "or theta_i,phi_i; the fit file holds every group (select one with --fit MODEL,theta_i=40)")
      ->allow_extra_args(false);
  c->add_option("--threads", args.threads, "Threads (per-wavelength mode; the results do not depend on it)")
      ->capture_default_str();
  c->add_option(
       "--joint-solver", args.joint_solver,
       "Joint mode linear solver (per-wavelength blocks eliminated first): " + described_names_text<JointSolver>())
      ->capture_default_str();
  c->add_option("--max-iterations", args.max_iterations, "Iteration limit per problem")->capture_default_str();
  c->add_flag("--no-covariance", args.no_covariance, "Skip standard errors and correlations");
  c->add_flag("--no-warm-start", args.no_warm_start,
              "Start every wavelength from the given start (default: from the previous wavelength's solution)");
  c->add_flag("--no-amplitude-solve", args.no_amplitude_solve,
              "Do not solve the linear amplitudes (parameters flagged linear) before each start");
  c->add_option("--residuals", args.residuals,
                "Write measured, fitted and residual values per geometry and wavelength (CSV)");
  c->add_option("-o,--output", args.output, "Fit file to write (JSON)")->required();
  add_quiet_flag(c, args.quiet);
  c->callback([] { run(args); });
}

}  // namespace roadbrdf::cli
