// White-sky (bi-hemispherical) albedo: outer Gauss-Kronrod panels in mu_i over black-sky inner
// integrals (see hemisphere.h for the rule and its accuracy).
#include <tbb/parallel_for.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "roadbrdf/albedo/black_sky_integrator.h"
#include "roadbrdf/albedo/gradient_integrals.h"
#include "roadbrdf/albedo/hemisphere.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"

namespace roadbrdf::albedo {

using detail::BlackSkyIntegrator;

namespace {

// Outer adaptive Gauss-Kronrod integral  int_0^1 2 mu F(mu) dmu  of an inner spectral integral F.
template <class Inner>
SpectralIntegral integrate_cosine_weighted(std::size_t n_sets, const QuadratureSettings& settings, Inner inner) {
  const KronrodRule& r = kronrod15();
  struct OuterPanel {
    double a, b;
    std::vector<double> q, err;
  };
  SpectralIntegral result;
  std::size_t geometries = 0;
  bool converged = true;
  auto make = [&](double a, double b) {
    OuterPanel p{a, b, std::vector<double>(n_sets, 0.0), std::vector<double>(n_sets, 0.0)};
    std::vector<double> qg(n_sets, 0.0), inner_err(n_sets, 0.0);
    const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
    // The 15 inner integrals are independent: computed in parallel (each deterministic), summed in
    // node order, so the result does not depend on the number of threads.
    std::array<SpectralIntegral, 15> f;
    tbb::parallel_for(0, 15, [&](int j) {
      const double mu = mid + half * r.x[j];
      // Inner tolerance tol / (4 mu): the inner errors then add at most (tol/2) (b - a) to the outer
      // estimate (sum_j w_j 2 mu_j tol/(4 mu_j) = tol/2 (b - a)), and grazing nodes, whose black-sky
      // integrals of specular lobes are the costliest, get the loosest tolerance.
      f[j] = inner(mu, std::min(0.05, settings.tolerance / (4.0 * mu)));
    });
    for (int j = 0; j < 15; ++j) {
      const double mu = mid + half * r.x[j];
      geometries += f[j].geometries;
      converged = converged && f[j].converged;
      const double wk = half * r.wk[j] * 2.0 * mu, wg = half * r.wg[j] * 2.0 * mu;
      for (std::size_t s = 0; s < n_sets; ++s) {
        p.q[s] += wk * f[j].value[s];
        qg[s] += wg * f[j].value[s];
        inner_err[s] += wk * f[j].error[s];
      }
    }
    for (std::size_t s = 0; s < n_sets; ++s) p.err[s] = std::fabs(p.q[s] - qg[s]) + inner_err[s];
    return p;
  };
  std::vector<OuterPanel> panels;
  panels.push_back(make(0.0, 1.0));
  std::vector<double> total(n_sets);
  while (true) {
    std::fill(total.begin(), total.end(), 0.0);
    for (const auto& p : panels) {
      for (std::size_t s = 0; s < n_sets; ++s) total[s] += p.err[s];
    }
    const std::size_t worst = settings.worst_set(total.data(), n_sets);
    if (worst == n_sets) break;
    if (geometries >= settings.max_geometries || panels.size() > 200) {
      converged = false;
      break;
    }
    std::size_t target = 0;
    for (std::size_t i = 1; i < panels.size(); ++i) {
      if (panels[i].err[worst] > panels[target].err[worst]) target = i;
    }
    const double a = panels[target].a, b = panels[target].b, m = 0.5 * (a + b);
    panels[target] = make(a, m);
    panels.push_back(make(m, b));
  }
  result.value.assign(n_sets, 0.0);
  result.error.assign(n_sets, 0.0);
  for (const auto& p : panels) {
    for (std::size_t s = 0; s < n_sets; ++s) {
      result.value[s] += p.q[s];
      result.error[s] += p.err[s];
    }
  }
  result.geometries = geometries;
  result.converged = converged;
  return result;
}

}  // namespace

namespace {

// True if f(w_i, w_r) = f(w_r, w_i) (Helmholtz reciprocity) to ~1e-10 relative at a fixed set of
// scattered geometries, for every parameter set.
bool is_reciprocal(const Model& model, const double* params, std::size_t n_sets) {
  std::vector<Geometry> g;
  for (int k = 0; k < 24; ++k) {
    // deterministic scattered angles (golden-ratio sequences), zeniths in (0, 88) deg
    const double u1 = std::fmod(0.5 + 0.6180339887498949 * k, 1.0), u2 = std::fmod(0.25 + 0.7548776662466927 * k, 1.0);
    const double u3 = std::fmod(0.1 + 0.5698402909980532 * k, 1.0);
    const double ti = u1 * 88.0 * kDegree, tr = u2 * 88.0 * kDegree, dphi = u3 * 2.0 * kPi;
    g.push_back(geometry_from_radians(ti, 0.3, tr, 0.3 + dphi));
    g.push_back(geometry_from_radians(tr, 0.3 + dphi, ti, 0.3));
  }
  std::vector<double> out(g.size() * n_sets);
  model.evaluate_batch(g.data(), g.size(), params, n_sets, out.data());
  for (std::size_t k = 0; k < g.size(); k += 2) {
    for (std::size_t s = 0; s < n_sets; ++s) {
      const double a = out[k * n_sets + s], b = out[(k + 1) * n_sets + s];
      if (!std::isfinite(a) || !std::isfinite(b) || std::fabs(a - b) > 1e-10 * (std::fabs(a) + std::fabs(b)) + 1e-300) {
        return false;
      }
    }
  }
  return true;
}

}  // namespace

namespace detail {

bool white_sky_reciprocal(const Model& model, const double* params, std::size_t n_sets) {
  return is_isotropic(model, params, n_sets) && is_reciprocal(model, params, n_sets);
}

SpectralIntegral white_sky_integral(const Model& model, const double* params, std::size_t n_sets,
                                    const QuadratureSettings& settings, bool reciprocal) {
  if (reciprocal) {
    // Reciprocity: int int_{mu_r > mu_i} = int int_{mu_r < mu_i}, so the inner integral runs over
    // mu_r in [0, mu_i] only and counts twice. Grazing mu_i (the costly black-sky integrals of lobes
    // near the horizon) then integrate over a thin band only, and Oren-Nayar's kink at
    // theta_r = theta_i lies on the boundary.
    return integrate_cosine_weighted(n_sets, settings, [&](double mu, double tolerance) {
      QuadratureSettings inner = settings;
      inner.tolerance = 0.5 * tolerance;
      BlackSkyIntegrator integrator(model, params, n_sets, std::acos(mu), 0.0, true);
      integrator.set_lower_triangle();
      SpectralIntegral r = integrator.run(inner);
      for (std::size_t s = 0; s < n_sets; ++s) {
        r.value[s] *= 2.0;
        r.error[s] *= 2.0;
      }
      return r;
    });
  }
  const bool isotropic = is_isotropic(model, params, n_sets);
  return integrate_cosine_weighted(n_sets, settings, [&](double mu, double tolerance) {
    QuadratureSettings inner = settings;
    inner.tolerance = tolerance;
    const double theta = std::acos(mu);
    return isotropic ? black_sky(model, params, n_sets, theta, 0.0, inner)
                     : black_sky_azimuth_mean(model, params, n_sets, theta, inner);
  });
}

}  // namespace detail

SpectralIntegral white_sky(const Model& model, const double* params, std::size_t n_sets,
                           const QuadratureSettings& settings) {
  return detail::white_sky_integral(model, params, n_sets, settings,
                                    detail::white_sky_reciprocal(model, params, n_sets));
}

}  // namespace roadbrdf::albedo
