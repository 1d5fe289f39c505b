// roadbrdf fit DATA.csv --model M [--model M2 ...] [...] -o FIT.json
// Fits each model to every wavelength of a measured spectral BRDF (fitting/fit.h), prints a
// ranking table and writes the fit file (fitting/fit_file.h), which every command accepts as a model.
#include <fmt/core.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/dataset_flags.h"
#include "roadbrdf/cli/common.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/fitting/fit.h"
#include "roadbrdf/fitting/fit_file.h"
#include "roadbrdf/core/csv.h"
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
  std::string loss = "plain";
  std::string robust = "none";
  bool solid_angle = false;
  bool no_sigma = false;
  int multistart = 1;
  unsigned seed = 1;
  std::string wavelengths;
  int threads = 1;
  int max_iterations = 200;
  bool no_covariance = false;
  std::string joint_solver = "dense-schur";
  bool no_warm_start = false;
  bool no_amplitude_solve = false;
  std::string residuals;
  std::string output;
};

// Progress bar on standard error, only on a terminal and only once a fit has run for a second.
class ProgressBar {
 public:
  ProgressBar(std::string label) : label_(std::move(label)), start_(std::chrono::steady_clock::now()),
                                   enabled_(isatty(fileno(stderr)) != 0) {}
  ~ProgressBar() {
    if (shown_) std::fprintf(stderr, "\n");
  }
  void update(std::size_t done, std::size_t total) {
    if (!enabled_ || total == 0) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (elapsed < 1.0) return;
    shown_ = true;
    const int width = 40;
    const int filled = static_cast<int>(static_cast<double>(width) * static_cast<double>(done) / static_cast<double>(total));
    std::string bar(static_cast<std::size_t>(std::clamp(filled, 0, width)), '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r%s [%s] %zu/%zu %.1f s", label_.c_str(), bar.c_str(), done, total, elapsed);
    std::fflush(stderr);
  }

 private:
  std::string label_;
  std::chrono::steady_clock::time_point start_;
  bool enabled_;
  bool shown_ = false;
};

std::vector<std::string> split_commas(const std::vector<std::string>& items) {
  std::vector<std::string> out;
  for (const auto& item : items) {
    std::string cur;
    for (char c : item + ",") {
      if (c == ',') {
        if (!cur.empty()) out.push_back(cur);
        cur.clear();
      } else if (c != ' ') {
        cur += c;
      }
    }
  }
  return out;
}

std::string number_or_dash(double x, const char* format) {
  return std::isfinite(x) ? fmt::format(fmt::runtime(format), x) : std::string("-");
}

void run(const FitArgs& a) {
  if (a.models.empty()) throw InputError("give at least one --model");
  if (a.output.empty()) throw InputError("give the output fit file with -o FIT.json");
  check_distinct_files({{"DATA", a.data}}, {{"-o", a.output}, {"--residuals", a.residuals}});
  std::FILE* report = report_stream(a.output);
  SpectralDataset data = read_dataset(a.data, dataset_read_options(a.read));
  if (!a.wavelengths.empty()) data = subset_wavelengths(data, select_wavelengths(data.wavelengths, a.wavelengths));

  const OptionSet given_options = parse_option_assignments(a.options, "--option");
  const std::map<std::string, double> fixed = parse_numeric_assignments(a.fixed, "--fix");
  const std::map<std::string, double> start = parse_numeric_assignments(a.start, "--start");
  const std::vector<std::string> shared = split_commas(a.shared);

  FitOptions base;
  base.loss = fit_loss_from_string(a.loss);
  robust_loss_from_string(a.robust, base.robust, base.robust_scale);
  base.solid_angle_weights = a.solid_angle;
  base.use_sigma = !a.no_sigma;
  base.multistart = a.multistart;
  base.seed = a.seed;
  base.threads = a.threads;
  base.max_iterations = a.max_iterations;
  base.compute_covariance = !a.no_covariance;
  base.warm_start = !a.no_warm_start;
  base.joint_solver = a.joint_solver;
  base.solve_linear = !a.no_amplitude_solve;

  // Options / fixed / start / shared names apply to every model that declares them; a name no
  // model declares is an error.
  std::set<std::string> used_options, used_parameters;
  std::vector<std::unique_ptr<Model>> models;
  std::vector<FitResult> fits;
  for (std::size_t i = 0; i < a.models.size(); ++i) {
    const std::string& name = a.models[i];
    const std::unique_ptr<Model> probe = make_model(name);
    std::set<std::string> declared;
    for (const auto& o : probe->description().options) declared.insert(o.name);
    OptionSet mine;
    for (const auto& [k, v] : given_options) {
      // Composites also accept a plain option name for their components (registry.h).
      bool accepted = declared.count(k) > 0;
      for (const auto& d : declared) accepted = accepted || (d.size() > k.size() && d.compare(d.size() - k.size() - 1, std::string::npos, "." + k) == 0);
      if (accepted) {
        mine[k] = v;
        used_options.insert(k);
      }
    }
    models.push_back(make_model(name, mine));
    const ModelDescription& desc = models.back()->description();
    FitOptions o = base;
    for (const auto& [k, v] : fixed) {
      if (desc.parameter_index(k)) {
        o.fixed[k] = v;
        used_parameters.insert(k);
      }
    }
    for (const auto& [k, v] : start) {
      if (desc.parameter_index(k)) {
        o.start[k] = v;
        used_parameters.insert(k);
      }
    }
    for (const auto& k : shared) {
      if (k == "auto") {
        for (const auto& p : desc.parameters) {
          if (!p.spectral && !o.fixed.count(p.name)) o.shared.push_back(p.name);
        }
        used_parameters.insert(k);
      } else if (desc.parameter_index(k)) {
        o.shared.push_back(k);
        used_parameters.insert(k);
      }
    }
    ProgressBar bar(fmt::format("fit {} ({}/{})", desc.name, i + 1, a.models.size()));
    o.progress = [&bar](std::size_t done, std::size_t total) { bar.update(done, total); };
    fits.push_back(fit_model(*models.back(), data, o));
  }
  for (const auto& [k, v] : given_options) {
    if (!used_options.count(k)) throw InputError("--option " + k + ": no fitted model has this option");
  }
  auto check_used = [&](const std::string& what, const std::string& k) {
    if (!used_parameters.count(k)) throw InputError(what + " " + k + ": no fitted model has this parameter (see `roadbrdf models`)");
  };
  for (const auto& [k, v] : fixed) check_used("--fix", k);
  for (const auto& [k, v] : start) check_used("--start", k);
  for (const auto& k : shared) check_used("--shared", k);

  // Ranking table (best BIC first).
  std::vector<std::size_t> order(fits.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
    return fits[x].bic_total < fits[y].bic_total;
  });
  const std::size_t M = data.wavelength_count();
  fmt::print(report, "# {} geometries x {} wavelengths ({}-{} nm), loss {}{}{}\n", data.geometry_count(), M,
             data.wavelengths.front(), data.wavelengths.back(), to_string(base.loss),
             base.robust == RobustLoss::kNone ? "" : ", robust " + to_string(base.robust),
             data.has_sigma() && base.use_sigma ? ", weights 1/sigma^2" : "");
  fmt::print(report, "{:<4} {:<36} {:>6} {:>12} {:>9} {:>9} {:>14} {:>14} {:>9} {:>8} {:>8}\n", "rank", "model", "k",
             "RMSE[sr^-1]", "relRMSE%", "maxrel%", "AIC", "BIC", "converged", "atbound", "time[s]");
  for (std::size_t r = 0; r < order.size(); ++r) {
    const FitResult& f = fits[order[r]];
    fmt::print(report, "{:<4} {:<36} {:>6} {:>12} {:>9} {:>9} {:>14} {:>14} {:>9} {:>8} {:>8.2f}\n", r + 1, f.model,
               f.free_parameters_total, number_or_dash(f.rmse_total, "{:.4g}"),
               number_or_dash(100.0 * f.relative_rmse_total, "{:.3g}"),
               number_or_dash(100.0 * f.max_relative_error_total, "{:.3g}"), number_or_dash(f.aic_total, "{:.2f}"),
               number_or_dash(f.bic_total, "{:.2f}"), fmt::format("{}/{}", f.converged_count, M), f.at_bound_count,
               f.seconds);
  }
  fmt::print(report, "best (lowest total BIC): {}\n", fits[order.front()].model);
  for (const auto& f : fits) {
    if (f.converged_count < M) {
      fmt::print(stderr, "roadbrdf: warning: {}: {} of {} wavelengths did not converge (see 'status' in {})\n",
                 f.model, M - f.converged_count, M, a.output);
    }
    if (f.at_bound_count > 0) {
      fmt::print(stderr, "roadbrdf: warning: {}: parameters on a bound at {} of {} wavelengths (see 'at_bounds')\n",
                 f.model, f.at_bound_count, M);
    }
    if (base.compute_covariance && f.covariance_failures > 0) {
      fmt::print(stderr, "roadbrdf: warning: {}: no standard errors at {} of {} wavelengths (see 'covariance_message')\n",
                 f.model, f.covariance_failures, M);
    }
  }
  write_fit_file(a.output, fits);
  if (!a.residuals.empty()) {
    std::vector<const Model*> ptrs;
    for (const auto& m : models) ptrs.push_back(m.get());
    AtomicFile out(a.residuals);
    write_residuals(out.stream(), data, ptrs, fits);
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
  c->add_option("--fix", args.fixed, "Hold a parameter NAME=VALUE at every wavelength (repeatable)")->allow_extra_args(false);
  c->add_option("--start", args.start, "Starting value NAME=VALUE (repeatable); model defaults otherwise")
      ->allow_extra_args(false);
  c->add_option("--loss", args.loss,
                "plain: f-y | relative: (f-y)/y | log: ln(1+f cos)-ln(1+y cos) (Loew 2012) | cosine: (f-y) cos "
                "(Ngan 2005)")
      ->capture_default_str();
  c->add_option("--robust", args.robust, "Robust loss huber:SCALE or cauchy:SCALE (SCALE in residual units), or none")
      ->capture_default_str();
  c->add_flag("--solid-angle-weights", args.solid_angle,
              "Weight each geometry by its solid-angle cell (nearest-neighbour estimate, fitting/fit.h)");
  c->add_flag("--no-sigma-weights", args.no_sigma, "Ignore the dataset's uncertainties (default: weights 1/sigma^2)");
  c->add_option("--multistart", args.multistart,
                "Starting points per fit: the start, then a Latin hypercube over the nonlinear parameters")
      ->capture_default_str();
  c->add_option("--seed", args.seed, "Seed of the multi-start points")->capture_default_str();
  c->add_option("--wavelengths", args.wavelengths, "Wavelengths to fit: START:STOP:STEP or a list, nm");
  c->add_option("--threads", args.threads, "Threads (per-wavelength mode; the results do not depend on it)")
      ->capture_default_str();
  c->add_option("--joint-solver", args.joint_solver,
                "Joint mode linear solver: dense-schur | sparse-schur | iterative-schur (per-wavelength blocks "
                "eliminated by a Schur complement)")
      ->capture_default_str();
  c->add_option("--max-iterations", args.max_iterations, "Iteration limit per problem")->capture_default_str();
  c->add_flag("--no-covariance", args.no_covariance, "Skip standard errors and correlations");
  c->add_flag("--no-warm-start", args.no_warm_start,
              "Start every wavelength from the given start (default: from the previous wavelength's solution)");
  c->add_flag("--no-amplitude-solve", args.no_amplitude_solve,
              "Do not solve the linear amplitudes (parameters flagged linear) before each start");
  c->add_option("--residuals", args.residuals, "Write measured, fitted and residual values per geometry and wavelength (CSV)");
  c->add_option("-o,--output", args.output, "Fit file to write (JSON)")->required();
  c->callback([] { run(args); });
}

}  // namespace roadbrdf::cli
