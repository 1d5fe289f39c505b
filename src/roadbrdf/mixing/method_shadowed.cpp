// Method "shadowed": nonlinear fitted mixing in which the coarse aggregates shadow the matrix
// (binder, mastic, fines) at grazing angles (mixing.h; the form is MixtureModel kind "shadowed",
// mixture_model.h). Weights and the shadowing coefficient are fitted with Ceres.
#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "roadbrdf/core/error.h"
#include "roadbrdf/mixing/method_support.h"
#include "roadbrdf/mixing/method_table.h"

namespace roadbrdf::mixing {

using namespace detail;

namespace {

// Cost of the shadowed mixture at one geometry: M residuals.
struct ShadowedResidual {
  const double* F;              // [k][m] of this geometry
  const double* y;              // [m]
  const double* inverse_sigma;  // [m], or nullptr (unweighted)
  std::size_t K, M;
  double path_tangent;  // tan theta_i + tan theta_r
  const std::vector<bool>* coarse;
  template <typename T>
  bool operator()(T const* const* p, T* residuals) const {
    const T* a = p[0];
    const T& s = p[1][0];
    T a_matrix(0.0), a_coarse(0.0);
    for (std::size_t k = 0; k < K; ++k) ((*coarse)[k] ? a_coarse : a_matrix) += a[k];
    using std::exp;
    const T S = exp(-s * path_tangent);
    const T boost = 1.0 + (1.0 - S) * a_matrix / (a_coarse + 1e-12);
    for (std::size_t m = 0; m < M; ++m) {
      T sum(0.0);
      for (std::size_t k = 0; k < K; ++k) sum += a[k] * ((*coarse)[k] ? boost : S) * F[k * M + m];
      residuals[m] = inverse_sigma ? (sum - y[m]) * inverse_sigma[m] : sum - y[m];
    }
    return true;
  }
};

struct SumToOneResidual {
  double scale;
  std::size_t K;
  template <typename T>
  bool operator()(T const* const* p, T* residual) const {
    T sum(0.0);
    for (std::size_t k = 0; k < K; ++k) sum += p[0][k];
    residual[0] = scale * (sum - 1.0);
    return true;
  }
};

}  // namespace

void mix_shadowed(const MethodCall& call, MixResult& r, std::vector<std::size_t>& members) {
  const MixInputs& inputs = call.inputs;
  const MixSettings& settings = call.settings;
  const Formulation& f = inputs.formulation;
  const SpectralDataset* data = call.data;
  std::map<std::string, double> info;
  if (f.mastic) {
    // The report's structure: the matrix between the coarse grains is the measured mastic.
    r.formulation_weights = mastic_weights(inputs, settings, members, info, r.notes);
  } else {
    r.formulation_weights = areal_weights(inputs, settings, members, info);
  }
  std::vector<double> grid;
  const LinearSystem sys = fitted_system(call, members, grid);
  const std::size_t K = members.size();
  std::vector<bool> coarse;
  for (std::size_t e : members) {
    const EndMember& em = inputs.end_members[e];
    bool all_coarse = !em.is_mastic && !em.components.empty();
    for (std::size_t i : em.components) all_coarse = all_coarse && is_coarse(f, f.components[i]);
    coarse.push_back(all_coarse);
  }
  if (std::none_of(coarse.begin(), coarse.end(), [](bool b) { return b; })) {
    throw InputError(
        "method 'shadowed' needs a coarse aggregate end-member (a fit file used only by aggregates "
        "with d_min_mm >= coarse_min_size_mm)");
  }
  if (std::all_of(coarse.begin(), coarse.end(), [](bool b) { return b; })) {
    throw InputError("method 'shadowed' needs a matrix end-member (binder, mastic or fines) besides the coarse ones");
  }
  std::vector<double> a = solve_weights(sys, 0, sys.M, settings.sum_to_one);
  double a_sum = std::accumulate(a.begin(), a.end(), 0.0);
  if (!(a_sum > 0.0)) a = r.formulation_weights;
  for (double& x : a) x = std::max(x, 1e-6);
  double s = 0.0;
  ceres::Problem problem;
  for (std::size_t row = 0; row < sys.rows.size(); ++row) {
    const Geometry& g = data->geometries[sys.rows[row]];
    const double ci = std::max(g.cos_theta_i(), 1e-9), cr = std::max(g.cos_theta_r(), 1e-9);
    const double path = std::sqrt(std::max(0.0, 1.0 - ci * ci)) / ci + std::sqrt(std::max(0.0, 1.0 - cr * cr)) / cr;
    auto* functor = new ShadowedResidual{sys.F.data() + row * K * sys.M,
                                         sys.y.data() + row * sys.M,
                                         sys.inverse_sigma.empty() ? nullptr : sys.inverse_sigma.data() + row * sys.M,
                                         K,
                                         sys.M,
                                         path,
                                         &coarse};
    auto* cost = new ceres::DynamicAutoDiffCostFunction<ShadowedResidual, 4>(functor);
    cost->AddParameterBlock(static_cast<int>(K));
    cost->AddParameterBlock(1);
    cost->SetNumResiduals(static_cast<int>(sys.M));
    problem.AddResidualBlock(cost, nullptr, a.data(), &s);
  }
  if (settings.sum_to_one) {
    // Scale of the penalty: the (weighted) data norm per geometry.
    double y2 = 0.0;
    for (std::size_t i = 0; i < sys.y.size(); ++i) {
      const double v = sys.inverse_sigma.empty() ? 1.0 : sys.inverse_sigma[i];
      y2 += sys.y[i] * sys.y[i] * v * v;
    }
    auto* cost = new ceres::DynamicAutoDiffCostFunction<SumToOneResidual, 4>(
        new SumToOneResidual{1e4 * std::sqrt(y2 / std::max<std::size_t>(1, sys.rows.size())), K});
    cost->AddParameterBlock(static_cast<int>(K));
    cost->SetNumResiduals(1);
    problem.AddResidualBlock(cost, nullptr, a.data());
  }
  for (std::size_t k = 0; k < K; ++k) {
    problem.SetParameterLowerBound(a.data(), static_cast<int>(k), 0.0);
    problem.SetParameterUpperBound(a.data(), static_cast<int>(k), 1e3);
  }
  problem.SetParameterLowerBound(&s, 0, 0.0);
  problem.SetParameterUpperBound(&s, 0, 100.0);
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 200;
  options.function_tolerance = 1e-12;
  options.parameter_tolerance = 1e-12;
  options.num_threads = 1;
  // Multi-start over s (the only nonlinear unknown); weights start from the NNLS solution.
  const std::vector<double> a_start = a;
  std::vector<double> best_a;
  double best_s = 0.0, best_cost = std::numeric_limits<double>::infinity();
  ceres::Solver::Summary best_summary;
  for (double s_start : {0.0, 0.1, 0.3, 1.0, 3.0}) {
    a = a_start;
    s = s_start;
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);
    if (summary.IsSolutionUsable() && summary.final_cost < best_cost) {
      best_cost = summary.final_cost;
      best_a = a;
      best_s = s;
      best_summary = summary;
    }
  }
  if (best_a.empty()) throw InputError("method 'shadowed': the fit failed from every start");
  a = best_a;
  s = best_s;
  if (best_summary.termination_type != ceres::CONVERGENCE) {
    r.notes.push_back("shadowed fit did not converge: " + best_summary.message);
  }
  r.weights = a;
  r.settings["shadowing"] = s;
  r.settings["sigma_weighted"] = sys.sigma_weighted ? 1.0 : 0.0;
  r.settings["sum_to_one"] = settings.sum_to_one ? 1.0 : 0.0;
  r.mixture = make_mixture(MixtureKind::kShadowed, inputs, members, coarse);
  r.model = std::make_shared<const SpectralModel>(
      build_table(r.mixture, inputs, members, grid, [&](std::size_t, double* row) {
        std::copy(a.begin(), a.end(), row);
        row[K] = s;
      }));
  weight_distance(r);
}

}  // namespace roadbrdf::mixing
