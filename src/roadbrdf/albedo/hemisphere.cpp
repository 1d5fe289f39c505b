#include "roadbrdf/albedo/hemisphere.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "roadbrdf/albedo/black_sky_integrator.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"

namespace roadbrdf::albedo {

double SpectralIntegral::max_error() const { return max_error(error.size()); }

double SpectralIntegral::max_error(std::size_t n) const {
  double e = 0.0;
  for (std::size_t s = 0; s < std::min(n, error.size()); ++s) e = std::max(e, error[s]);
  return e;
}

const KronrodRule& kronrod15() {
  // QUADPACK qk15 (Piessens, de Doncker-Kapenga, Ueberhuber, Kahaner 1983): abscissae and weights of
  // the 15-point Kronrod rule and of the embedded 7-point Gauss rule on [-1, 1].
  static const KronrodRule rule = [] {
    const double xgk[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                           0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                           0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                           0.207784955007898467600689403773245, 0.0};
    const double wgk[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                           0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                           0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                           0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
    const double wg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                          0.381830050505118944950369775488975, 0.417959183673469387755102040816327};
    KronrodRule r{};
    for (int k = 0; k < 8; ++k) {
      // ascending order: index k is -xgk[k], index 14 - k is +xgk[k]
      r.x[k] = -xgk[k];
      r.x[14 - k] = xgk[k];
      r.wk[k] = r.wk[14 - k] = wgk[k];
      const double g = (k % 2 == 1) ? wg[k / 2] : 0.0;
      r.wg[k] = r.wg[14 - k] = g;
    }
    return r;
  }();
  return rule;
}

using detail::BlackSkyIntegrator;

bool is_isotropic(const Model& model, const double* params, std::size_t n_sets) {
  // The model's own claim (ModelDescription::isotropic), at every parameter set.
  for (std::size_t s = 0; s < n_sets; ++s) {
    if (!is_isotropic_at(model.description(), params + s * model.parameter_count())) return false;
  }
  return true;
}

// Sun zenith from which black_sky() cross-checks the (mu, dphi) rule with the mirror-polar rule.
constexpr double kGrazingCheck = 70.0 * kDegree;

bool grazing_check_applies(const Model& model, double theta_s, const QuadratureSettings& settings) {
  // A model without a lobe about the mirror direction (ModelDescription::mirror_lobe, checked by
  // tests/albedo/mirror_lobe_test.cpp) has nothing the check could find.
  return settings.grazing_check && model.description().mirror_lobe && theta_s >= kGrazingCheck;
}

SpectralIntegral black_sky(const Model& model, const double* params, std::size_t n_sets, double theta_s, double phi_s,
                           const QuadratureSettings& settings) {
  const bool isotropic = is_isotropic(model, params, n_sets);
  // First the (mu, dphi) rule with a quarter of the budget; if a sharp lobe keeps it from converging,
  // the mirror-polar rule, and the result with the smaller error estimate.
  QuadratureSettings first = settings;
  first.max_geometries = std::max<std::size_t>(1, settings.max_geometries / 4);
  BlackSkyIntegrator integrator(model, params, n_sets, theta_s, phi_s, isotropic);
  SpectralIntegral a = integrator.run(first);
  if (a.converged && !grazing_check_applies(model, theta_s, settings)) return a;
  if (a.converged) {
    // Towards grazing incidence a specular lobe of width alpha is only ~2 alpha cos(theta_s) wide in
    // azimuth: the (mu, dphi) rule's first nodes can all miss it, and then every error estimate is
    // zero (a KSK lobe of roughness 0.01 at 89 deg was missed entirely). The mirror-polar rule centres
    // its graded panels on the lobe. Both are run; where they disagree beyond their error estimates,
    // the larger value is kept for a non-negative BRDF (an unresolved peak of a positive integrand
    // can only be missed, never invented).
    const std::unique_ptr<FixedSetEvaluator> fixed = detail::own_fixed_sets(model, params, n_sets);
    BlackSkyIntegrator polar(model, params, n_sets, theta_s, phi_s, isotropic, true, fixed.get());
    SpectralIntegral b = polar.run(settings);
    const bool non_negative = model.description().non_negative;
    SpectralIntegral out = a;
    out.geometries = a.geometries + b.geometries;
    out.lobes_checked = b.converged;
    const std::size_t steering = settings.steering(n_sets);
    for (std::size_t s = 0; s < n_sets; ++s) {
      const double gap = std::fabs(a.value[s] - b.value[s]);
      if (gap <= a.error[s] + b.error[s] + settings.tolerance) continue;
      if (s < steering) out.lobes_checked = false;
      const bool take_b = b.converged && (non_negative ? b.value[s] > a.value[s] : b.error[s] < a.error[s]);
      if (take_b) {
        out.value[s] = b.value[s];
        out.error[s] = b.error[s];
      }
    }
    return out;
  }
  QuadratureSettings second = settings;
  second.max_geometries = settings.max_geometries - std::min(settings.max_geometries, a.geometries);
  const std::unique_ptr<FixedSetEvaluator> fixed = detail::own_fixed_sets(model, params, n_sets);
  BlackSkyIntegrator polar(model, params, n_sets, theta_s, phi_s, isotropic, true, fixed.get());
  SpectralIntegral b = polar.run(second);
  const std::size_t total = a.geometries + b.geometries;
  const std::size_t steering = settings.steering(n_sets);
  SpectralIntegral& best = (b.converged || b.max_error(steering) < a.max_error(steering)) ? b : a;
  best.geometries = total;
  return std::move(best);
}

SpectralIntegral black_sky_mirror_polar(const Model& model, const double* params, std::size_t n_sets, double theta_s,
                                        double phi_s, const QuadratureSettings& settings) {
  const std::unique_ptr<FixedSetEvaluator> fixed = detail::own_fixed_sets(model, params, n_sets);
  BlackSkyIntegrator integrator(model, params, n_sets, theta_s, phi_s, is_isotropic(model, params, n_sets), true,
                                fixed.get());
  return integrator.run(settings);
}

SpectralIntegral black_sky_mirror_polar_fixed(const Model& model, const double* params, std::size_t n_sets,
                                              double theta_s, double phi_s, int s_panels, int psi_intervals) {
  const std::unique_ptr<FixedSetEvaluator> fixed = detail::own_fixed_sets(model, params, n_sets);
  BlackSkyIntegrator integrator(model, params, n_sets, theta_s, phi_s, is_isotropic(model, params, n_sets), true,
                                fixed.get());
  return integrator.run_fixed(std::max(1, s_panels), psi_intervals);
}

SpectralIntegral black_sky_fixed(const Model& model, const double* params, std::size_t n_sets, double theta_s,
                                 double phi_s, int mu_panels, int phi_intervals) {
  BlackSkyIntegrator integrator(model, params, n_sets, theta_s, phi_s, is_isotropic(model, params, n_sets));
  return integrator.run_fixed(std::max(1, mu_panels), phi_intervals);
}

SpectralIntegral black_sky_azimuth_mean(const Model& model, const double* params, std::size_t n_sets, double theta_s,
                                        const QuadratureSettings& settings) {
  if (is_isotropic(model, params, n_sets)) return black_sky(model, params, n_sets, theta_s, 0.0, settings);
  // Periodic trapezoid in the sun azimuth, doubled until |T_N - T_N/2| + inner errors <= tolerance.
  QuadratureSettings inner = settings;
  inner.tolerance = 0.5 * settings.tolerance;
  SpectralIntegral result;
  std::vector<SpectralIntegral> samples;  // at phi = 2 pi k / n
  int n = 4;
  samples.reserve(n);
  for (int k = 0; k < n; ++k) samples.push_back(black_sky(model, params, n_sets, theta_s, 2.0 * kPi * k / n, inner));
  auto mean_of = [&](int stride) {
    std::vector<double> m(n_sets, 0.0), e(n_sets, 0.0);
    int count = 0;
    for (std::size_t k = 0; k < samples.size(); k += static_cast<std::size_t>(stride)) {
      for (std::size_t s = 0; s < n_sets; ++s) {
        m[s] += samples[k].value[s];
        e[s] += samples[k].error[s];
      }
      ++count;
    }
    for (std::size_t s = 0; s < n_sets; ++s) {
      m[s] /= count;
      e[s] /= count;
    }
    return std::make_pair(m, e);
  };
  while (true) {
    auto [fine, inner_err] = mean_of(1);
    auto [coarse, unused] = mean_of(2);
    result.value = fine;
    result.error.assign(n_sets, 0.0);
    for (std::size_t s = 0; s < n_sets; ++s) result.error[s] = std::fabs(fine[s] - coarse[s]) + inner_err[s];
    std::size_t geometries = 0;
    bool converged = true, lobes_checked = true;
    for (const auto& x : samples) {
      geometries += x.geometries;
      converged = converged && x.converged;
      lobes_checked = lobes_checked && x.lobes_checked;
    }
    result.geometries = geometries;
    result.converged = converged;
    result.lobes_checked = lobes_checked;
    if (settings.worst_set(result.error.data(), n_sets) == n_sets) break;
    if (n >= 256 || geometries >= settings.max_geometries) {
      result.converged = false;
      break;
    }
    // Double: interleave new samples at odd positions.
    std::vector<SpectralIntegral> doubled;
    for (int k = 0; k < n; ++k) {
      doubled.push_back(std::move(samples[static_cast<std::size_t>(k)]));
      doubled.push_back(black_sky(model, params, n_sets, theta_s, 2.0 * kPi * (2 * k + 1) / (2 * n), inner));
    }
    samples = std::move(doubled);
    n *= 2;
  }
  return result;
}

}  // namespace roadbrdf::albedo
