#include "roadbrdf/fitting/starting_points.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "roadbrdf/core/random.h"

namespace roadbrdf::fitting {

void nudge_off_bounds(const ParameterLayout& L, std::vector<double>& x) {
  for (std::size_t k : L.free_nonlinear) {
    const double lo = L.info[k].lower, hi = L.info[k].upper;
    const double step = 1e-4 * std::min(hi - lo, 1.0);
    if (x[k] <= lo) x[k] = lo + step;
    if (x[k] >= hi) x[k] = hi - step;
  }
}

void solve_amplitudes(const FitData& d, const ParameterLayout& L, std::size_t w, std::vector<double>& x) {
  const std::size_t k = L.free_linear.size();
  if (k == 0) return;
  const std::size_t n = d.n, p = d.p;
  std::vector<double> f(n), J(n * p);
  d.model->evaluate_prepared_with_gradient(*d.prepared_geometries, x.data(), f.data(), J.data());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(k));
  Eigen::VectorXd b = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(k));
  const double* yw = d.y.data() + w * n;
  const double* qw = d.lin_weight.data() + w * n;
  for (std::size_t g = 0; g < n; ++g) {
    double f0 = f[g];
    for (std::size_t a = 0; a < k; ++a) f0 -= x[L.free_linear[a]] * J[g * p + L.free_linear[a]];
    const double q2 = qw[g] * qw[g];
    if (!std::isfinite(f0) || !std::isfinite(q2)) return;
    for (std::size_t a = 0; a < k; ++a) {
      const double ga = J[g * p + L.free_linear[a]];
      b[static_cast<Eigen::Index>(a)] += q2 * ga * (yw[g] - f0);
      for (std::size_t c = 0; c < k; ++c) {
        A(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(c)) += q2 * ga * J[g * p + L.free_linear[c]];
      }
    }
  }
  std::vector<double> a(k);
  for (std::size_t i = 0; i < k; ++i) a[i] = x[L.free_linear[i]];
  for (int sweep = 0; sweep < 300; ++sweep) {
    double change = 0.0;
    for (std::size_t i = 0; i < k; ++i) {
      const auto ii = static_cast<Eigen::Index>(i);
      if (!(A(ii, ii) > 0.0)) continue;
      double s = b[ii];
      for (std::size_t c = 0; c < k; ++c) {
        if (c != i) s -= A(ii, static_cast<Eigen::Index>(c)) * a[c];
      }
      const ParameterInfo& info = L.info[L.free_linear[i]];
      const double v = std::clamp(s / A(ii, ii), info.lower, info.upper);
      change = std::max(change, std::fabs(v - a[i]) / (std::fabs(v) + 1e-300));
      a[i] = v;
    }
    if (change < 1e-12) break;
  }
  std::vector<double> trial = x;
  for (std::size_t i = 0; i < k; ++i) trial[L.free_linear[i]] = a[i];
  // f holds the model at x already (its values from the gradient evaluation).
  if (d.chi2(w, trial.data()) < d.chi2_of_values(w, f.data())) x = trial;
}

std::vector<std::vector<double>> latin_hypercube(const ParameterLayout& L, const std::vector<double>& base, int count,
                                                 unsigned seed) {
  std::vector<std::vector<double>> points(static_cast<std::size_t>(std::max(count, 0)), base);
  if (count <= 0) return points;
  Rng rng(seed);
  for (std::size_t k : L.free_nonlinear) {
    double lo = L.info[k].lower, hi = L.info[k].upper;
    // Very wide bounds (e.g. 0..1e6 for an exponent): sample up to 10x the start instead.
    if (hi - lo > 1e3 * std::max(1.0, std::fabs(base[k])))
      hi = std::min(hi, lo + std::max(10.0 * std::fabs(base[k]), 1.0));
    std::vector<int> perm(static_cast<std::size_t>(count));
    std::iota(perm.begin(), perm.end(), 0);
    shuffle(perm, rng);
    for (int i = 0; i < count; ++i) {
      const double t = (perm[static_cast<std::size_t>(i)] + rng.uniform()) / count;
      points[static_cast<std::size_t>(i)][k] = lo + t * (hi - lo);
    }
  }
  return points;
}

}  // namespace roadbrdf::fitting
