// fit_model: validation of the request, the parameter layout, the data and loss multipliers, the
// dispatch to the per-wavelength or joint mode (per_wavelength.cpp, joint.cpp) and the totals.
#include "roadbrdf/fitting/fit.h"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <sstream>
#include <string>

#include "roadbrdf/core/error.h"
#include "roadbrdf/fitting/joint.h"
#include "roadbrdf/fitting/losses.h"
#include "roadbrdf/fitting/per_wavelength.h"
#include "roadbrdf/fitting/starting_points.h"

namespace roadbrdf {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string fmt_double(double x) {
  std::ostringstream s;
  s.precision(10);
  s << x;
  return s.str();
}

// The checks of the dataset's shape and of the options that need no model.
void check_request(const SpectralDataset& data, const FitOptions& options) {
  const std::size_t N = data.geometry_count(), M = data.wavelength_count();
  if (N == 0) throw InputError("cannot fit: the dataset has no geometries");
  if (M == 0) throw InputError("cannot fit: the dataset has no wavelengths");
  if (data.brdf.size() != N * M)
    throw InputError("cannot fit: dataset BRDF table does not match its geometries x wavelengths");
  if (data.has_sigma() && data.sigma.size() != N * M)
    throw InputError("cannot fit: dataset sigma table has the wrong size");
  check_fit_counts(options.multistart, options.threads, options.max_iterations);
}

// Measured geometries per wavelength. NaN is a missing value (masked out at its wavelength); an
// infinite value is an error.
std::vector<std::size_t> measured_counts(const SpectralDataset& data) {
  const std::size_t N = data.geometry_count(), M = data.wavelength_count();
  std::vector<std::size_t> measured_count(M, 0);
  for (std::size_t g = 0; g < N; ++g) {
    for (std::size_t w = 0; w < M; ++w) {
      const double y = data.value(g, w);
      if (std::isnan(y)) continue;
      if (!std::isfinite(y)) {
        throw InputError("cannot fit: BRDF value at geometry " + std::to_string(g + 1) + ", wavelength " +
                         fmt_double(data.wavelengths[w]) + " nm is " + fmt_double(y) + " (not a finite number)");
      }
      ++measured_count[w];
    }
  }
  return measured_count;
}

// Index of the parameter `name` of the model; `what` names the option in the error.
std::size_t parameter_index(const ModelDescription& desc, const std::string& name, const std::string& what) {
  const auto idx = desc.parameter_index(name);
  if (!idx) {
    std::string known;
    for (const auto& q : desc.parameters) known += (known.empty() ? "" : ", ") + q.name;
    throw InputError(what + ": model '" + desc.name + "' has no parameter '" + name + "' (parameters: " + known + ")");
  }
  return *idx;
}

// The fitting ranges given by options.bounds (narrower or wider than the default fitting range,
// inside what the physics allows); a default start outside them moves to their middle.
void apply_bounds(const ModelDescription& desc, const FitOptions& options, fitting::ParameterLayout& L) {
  for (const auto& [name, range] : options.bounds) {
    const std::size_t k = parameter_index(desc, name, "bounds");
    ParameterInfo& q = L.info[k];
    const auto [lo, hi] = range;
    const auto [physical_lo, physical_hi] = desc.physical_range(k);
    if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi) || lo < physical_lo || hi > physical_hi) {
      throw FieldError("bounds." + name, "[" + fmt_double(lo) + ", " + fmt_double(hi) +
                                             "] must be an interval lower < upper inside the parameter's physical "
                                             "range [" +
                                             fmt_double(physical_lo) + ", " + fmt_double(physical_hi) + "] " + q.unit +
                                             " (model metadata; the default fitting range is [" + fmt_double(q.lower) +
                                             ", " + fmt_double(q.upper) + "])");
    }
    q.lower = lo;
    q.upper = hi;
    if (L.start[k] < lo || L.start[k] > hi) L.start[k] = 0.5 * (lo + hi);
  }
}

// Which parameters are fixed, shared or free, their ranges and starting values (options.bounds,
// start, fixed, shared), checked against the model.
fitting::ParameterLayout parameter_layout(const ModelDescription& desc, std::size_t p, const FitOptions& options) {
  fitting::ParameterLayout L;
  L.info = desc.parameters;
  L.fixed.assign(p, false);
  L.shared.assign(p, false);
  L.start = desc.default_parameters();
  apply_bounds(desc, options, L);
  for (const auto& [name, value] : options.start) L.start[parameter_index(desc, name, "start")] = value;
  for (const auto& [name, value] : options.fixed) {
    const std::size_t k = parameter_index(desc, name, "fixed parameter");
    L.fixed[k] = true;
    L.start[k] = value;
  }
  for (std::size_t k = 0; k < p; ++k) {
    const ParameterInfo& q = L.info[k];
    if (!std::isfinite(L.start[k]) || L.start[k] < q.lower || L.start[k] > q.upper) {
      throw InputError(std::string(L.fixed[k] ? "fixed value" : "starting value") + " of '" + q.name +
                       "' = " + fmt_double(L.start[k]) + " is outside its bounds [" + fmt_double(q.lower) + ", " +
                       fmt_double(q.upper) + "] " + q.unit);
    }
  }
  for (const auto& name : options.shared) {
    const std::size_t k = parameter_index(desc, name, "shared parameter");
    if (L.fixed[k]) throw InputError("parameter '" + name + "' is both fixed and shared: give only one of them");
    L.shared[k] = true;
  }
  for (std::size_t k = 0; k < p; ++k) {
    if (L.fixed[k]) continue;
    if (L.info[k].linear && !L.shared[k]) {
      L.free_linear.push_back(k);
    } else if (!L.info[k].linear) {
      L.free_nonlinear.push_back(k);
    }
  }
  return L;
}

// Free parameters: all, the shared ones (one value for every wavelength), the per-wavelength ones.
struct FreeCounts {
  std::size_t all = 0, shared = 0, local = 0;
};

FreeCounts free_counts(const fitting::ParameterLayout& L) {
  FreeCounts c;
  for (std::size_t k = 0; k < L.fixed.size(); ++k) {
    if (!L.fixed[k]) {
      ++c.all;
      if (L.shared[k]) ++c.shared;
    }
  }
  c.local = c.all - c.shared;
  return c;
}

// Enough measured values for the free parameters: per wavelength, and in joint mode also overall.
void check_enough_data(const SpectralDataset& data, const std::vector<std::size_t>& measured_count,
                       const FreeCounts& free_params, bool joint, const std::string& model_name) {
  const std::size_t N = data.geometry_count(), M = data.wavelength_count();
  if (!joint && N < free_params.all) {
    throw InputError("cannot fit: " + std::to_string(N) + " geometries for " + std::to_string(free_params.all) +
                     " free parameters of '" + model_name + "' (fix some, or measure more geometries)");
  }
  for (std::size_t w = 0; w < M; ++w) {
    if (measured_count[w] < (joint ? free_params.local : free_params.all) || measured_count[w] == 0) {
      throw InputError("cannot fit: at " + fmt_double(data.wavelengths[w]) + " nm only " +
                       std::to_string(measured_count[w]) + " of " + std::to_string(N) +
                       " geometries were measured (the others are missing values), for " +
                       std::to_string(joint ? free_params.local : free_params.all) + " free parameters of '" +
                       model_name + "' (leave that wavelength out with `wavelengths`, or fix some parameters)");
    }
  }
  if (joint && (N < free_params.local || N * M < free_params.local * M + free_params.shared)) {
    throw InputError("cannot fit: " + std::to_string(N) + " geometries per wavelength for " +
                     std::to_string(free_params.local) + " free per-wavelength parameters (+" +
                     std::to_string(free_params.shared) + " shared)");
  }
  if (joint && free_params.local + free_params.shared == 0) throw InputError("cannot fit: every parameter is fixed");
}

// The loss multipliers of the measured value y at geometry g (0-based) and wavelength index w: m
// multiplies the residual (f - y) of the loss, lin weighs (f - y) in its linearisation. m starts as
// sqrt(solid-angle weight) / sigma; c = cos(theta_i).
void apply_loss(const SpectralDataset& data, FitLoss loss, std::size_t g, std::size_t w, double y, double c, double& m,
                double& lin) {
  switch (loss) {
    case FitLoss::kRelative:
      if (y == 0.0) {
        throw InputError("cannot use the relative loss: measured BRDF is 0 at geometry " + std::to_string(g + 1) +
                         ", wavelength " + fmt_double(data.wavelengths[w]) + " nm");
      }
      m /= std::fabs(y);
      lin = m;
      break;
    case FitLoss::kCosine:
      m *= c;
      lin = m;
      break;
    case FitLoss::kLog:
      if (!(1.0 + y * c > 0.0)) {
        throw InputError("cannot use the log loss: 1 + f cos(theta_i) <= 0 at geometry " + std::to_string(g + 1) +
                         ", wavelength " + fmt_double(data.wavelengths[w]) + " nm");
      }
      lin = m * c / (1.0 + y * c);
      break;
    default:
      break;
  }
}

// The data (wavelength-major) and the loss multipliers; `missing` counts the missing values.
// `start`: the starting parameters, whose fixed ones the model may prepare for (Model::prepare_expecting).
fitting::FitData fit_data(const Model& model, const SpectralDataset& data, const FitOptions& options,
                          const std::vector<double>& start, const std::vector<std::size_t>& measured_count,
                          std::size_t& missing) {
  const std::size_t p = model.parameter_count();
  const std::size_t N = data.geometry_count(), M = data.wavelength_count();
  fitting::FitData d;
  d.model = &model;
  d.p = p;
  d.n = N;
  d.m = M;
  d.loss = options.loss;
  d.robust = options.robust;
  d.robust_b = options.robust_scale * options.robust_scale;
  if (options.robust != RobustLoss::kNone && !(options.robust_scale > 0.0)) {
    throw InputError("the robust loss scale must be positive");
  }
  d.geometries = data.geometries.data();
  d.prepared_geometries = model.prepare_expecting(d.geometries, N, start.data());
  d.y.resize(N * M);
  d.mult.resize(N * M);
  d.lin_weight.resize(N * M);
  d.measured.assign(N * M, 1);
  d.measured_count = measured_count;
  d.cos_i.resize(N);
  for (std::size_t g = 0; g < N; ++g) d.cos_i[g] = data.geometries[g].cos_theta_i();
  const std::vector<double> sa =
      options.solid_angle_weights ? solid_angle_weights(data.geometries) : std::vector<double>(N, 1.0);
  const bool use_sigma = options.use_sigma && data.has_sigma();
  missing = 0;
  for (std::size_t w = 0; w < M; ++w) {
    for (std::size_t g = 0; g < N; ++g) {
      const double y = data.value(g, w);
      if (std::isnan(y)) {
        d.y[w * N + g] = 0.0;
        d.mult[w * N + g] = 0.0;
        d.lin_weight[w * N + g] = 0.0;
        d.measured[w * N + g] = 0;
        ++missing;
        continue;
      }
      double m = std::sqrt(sa[g]);
      if (use_sigma) {
        const double s = data.sigma[g * M + w];
        if (!(s > 0.0) || !std::isfinite(s)) {
          throw InputError("cannot fit: uncertainty at geometry " + std::to_string(g + 1) + ", wavelength " +
                           fmt_double(data.wavelengths[w]) + " nm is " + fmt_double(s) +
                           " (must be > 0; or fit without uncertainties)");
        }
        m /= s;
      }
      double lin = m;
      apply_loss(data, options.loss, g, w, y, d.cos_i[g], m, lin);
      d.y[w * N + g] = y;
      d.mult[w * N + g] = m;
      d.lin_weight[w * N + g] = lin;
    }
  }
  return d;
}

// The result's description of the fit before solving: model, parameters, the request, coverage.
FitResult result_header(const ModelDescription& desc, const fitting::ParameterLayout& L, const FitOptions& options,
                        const SpectralDataset& data, std::size_t missing, bool joint) {
  const std::size_t N = data.geometry_count(), M = data.wavelength_count();
  FitResult result;
  result.model = desc.name;
  result.options = desc.option_values;
  for (const auto& q : desc.parameters) {
    result.parameter_names.push_back(q.name);
    result.parameter_units.push_back(q.unit);
  }
  for (std::size_t k = 0; k < L.fixed.size(); ++k) {
    if (L.fixed[k]) result.fixed.push_back(L.info[k].name);
    if (L.shared[k]) result.shared.push_back(L.info[k].name);
  }
  result.settings = options;
  result.settings.progress = nullptr;
  result.missing_values = missing;
  std::vector<Geometry> measured;
  for (std::size_t g = 0; g < N; ++g) {
    for (std::size_t w = 0; w < M; ++w) {
      if (!std::isnan(data.value(g, w))) {
        measured.push_back(data.geometries[g]);
        break;
      }
    }
  }
  result.coverage = angular_coverage(measured);
  result.joint = joint;
  return result;
}

// A wavelength whose free nonlinear parameters all ended where they started (within 1e-9 relative).
bool stayed_at_start(const fitting::ParameterLayout& L, const WavelengthFit& out) {
  bool stayed = true;
  for (std::size_t k : L.free_nonlinear) {
    const double s0 = L.start[k];
    if (std::fabs(out.parameters[k] - s0) > 1e-9 * std::max(1.0, std::fabs(s0))) stayed = false;
  }
  return stayed;
}

// Totals over the wavelengths: RMSE, relative RMSE, chi^2, counts, and AIC/BIC of the Gaussian
// likelihood with the variance estimated per wavelength.
void add_totals(const SpectralDataset& data, const fitting::FitData& d, const fitting::ParameterLayout& L,
                const FreeCounts& free_params, bool joint, FitResult& result) {
  const std::size_t N = data.geometry_count(), M = data.wavelength_count();
  double ss = 0.0, sum_abs = 0.0, ll = 0.0;
  for (std::size_t w = 0; w < M; ++w) {
    WavelengthFit& out = result.wavelengths[w];
    out.wavelength = data.wavelengths[w];
    const double nw = static_cast<double>(out.points);  // measured geometries at w
    ss += out.rmse * out.rmse * nw;
    for (std::size_t g = 0; g < N; ++g) sum_abs += std::fabs(d.y[w * N + g]);  // 0 where missing
    result.max_relative_error_total = std::max(result.max_relative_error_total, out.max_relative_error);
    result.chi2_total += out.chi2;
    result.points_total += out.points;
    ll += nw * std::log(std::max(out.chi2 / nw, std::numeric_limits<double>::min()));
    if (out.converged) ++result.converged_count;
    if (!out.at_bounds.empty()) ++result.at_bound_count;
    if (!out.covariance_ok) ++result.covariance_failures;
    if (!L.free_nonlinear.empty()) {
      out.stayed_at_start = stayed_at_start(L, out);
      if (out.stayed_at_start && out.converged) ++result.stayed_at_start_count;
    }
  }
  result.free_parameters_total = joint ? free_params.shared + M * free_params.local : M * free_params.all;
  const double nt = static_cast<double>(result.points_total);
  result.rmse_total = std::sqrt(ss / nt);
  result.relative_rmse_total = sum_abs > 0.0 ? result.rmse_total / (sum_abs / nt) : kNaN;
  const double kt = static_cast<double>(result.free_parameters_total);
  result.aic_total = ll + 2.0 * kt;
  result.bic_total = ll + kt * std::log(static_cast<double>(N));
}

}  // namespace

void check_fit_counts(int multistart, int threads, int max_iterations) {
  if (multistart < 1 || multistart > kMaxMultistart) {
    throw FieldError("multistart",
                     fmt::format("{} is outside [1, {}] (each start is a whole fit)", multistart, kMaxMultistart));
  }
  if (threads < 1 || threads > kMaxFitThreads) {
    throw FieldError("threads", fmt::format("{} is outside [1, {}]", threads, kMaxFitThreads));
  }
  if (max_iterations < 1 || max_iterations > kMaxFitIterations) {
    throw FieldError("max_iterations", fmt::format("{} is outside [1, {}]", max_iterations, kMaxFitIterations));
  }
}

FitResult fit_model(const Model& model, const SpectralDataset& data, const FitOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  const ModelDescription& desc = model.description();
  check_request(data, options);
  const std::vector<std::size_t> measured_count = measured_counts(data);
  const fitting::ParameterLayout L = parameter_layout(desc, model.parameter_count(), options);
  const bool joint = !options.shared.empty();
  const FreeCounts free_params = free_counts(L);
  check_enough_data(data, measured_count, free_params, joint, desc.name);
  std::size_t missing = 0;
  const fitting::FitData d = fit_data(model, data, options, L.start, measured_count, missing);
  FitResult result = result_header(desc, L, options, data, missing, joint);
  if (joint) {
    fitting::fit_joint(d, L, options, result);
  } else {
    fitting::fit_per_wavelength(d, L, options, result);
  }
  add_totals(data, d, L, free_params, joint, result);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  result.cpu_seconds = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  return result;
}

std::vector<double> fitted_values(const Model& model, const SpectralDataset& data, const FitResult& fit) {
  const std::size_t N = data.geometry_count(), M = data.wavelength_count();
  if (fit.wavelengths.size() != M) throw InputError("fit and dataset have different wavelengths");
  std::vector<double> out(N * M), col(N);
  for (std::size_t w = 0; w < M; ++w) {
    model.evaluate_batch(data.geometries.data(), N, fit.wavelengths[w].parameters.data(), 1, col.data());
    for (std::size_t g = 0; g < N; ++g) out[g * M + w] = col[g];
  }
  return out;
}

}  // namespace roadbrdf
