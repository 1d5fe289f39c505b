// Hemispherical integrals of a BRDF: black-sky (directional-hemispherical) and white-sky
// (bi-hemispherical) albedo, for many parameter sets (wavelengths) at once.
//
// Definitions (report eqs. 2.21 and 2.22; eqs. 2.17/2.18 miss the cos(theta_r) sin(theta_r) factor,
// docs/report-corrections.md):
//   alpha_bs(theta_s, phi_s) = int_{2pi} f_r(w_s, w_r) cos(theta_r) dw_r  (+ R(theta_s) of an ideal specular part)
//   alpha_ws = (1/pi) int_{2pi} alpha_bs(w_i) cos(theta_i) dw_i  = 2 int_0^1 alpha_bs(mu) mu dmu  (isotropic)
//
// Quadrature (deterministic, adaptive, one set of geometries for every parameter set):
//   - mu = cos(theta_r) on [0, 1]: composite 15-point Gauss-Kronrod panels (the 7-point Gauss-Legendre
//     rule is embedded; |K15 - G7| is the error estimate). The initial panels are split at the specular
//     direction mu = cos(theta_s) (also where Oren-Nayar's min/max(theta_i, theta_r) has its kink).
//   - relative azimuth dphi = phi_r - phi_s: split at pi/2 and at the specular plane pi (and 3pi/2 for
//     anisotropic models, which use all of [0, 2 pi); isotropic models use [0, pi] twice, the integrand
//     being even about 0 and pi). On each quarter, the trapezoid rule after Sidi's sin^4 transformation
//     (dense nodes at the quarter ends, O(h^6) although Oren-Nayar has kinks at dphi = pi/2). The 15
//     nodes of a mu panel share one azimuth count (so the azimuth integral is a smooth function of mu
//     within the panel); doubling it reuses every node; |T_N - T_N/2| is each node's estimate.
//     (Not the plain periodic trapezoid: it is only O(h^2) at Oren-Nayar's |cos dphi| kinks and needs
//     256-1024 intervals at grazing incidence.)
//   - Adaptivity: while the summed error estimate of the worst parameter set exceeds the tolerance, the
//     panel contributing most to it is refined in the direction of its larger estimate (its mu error or
//     one of its nodes' azimuth errors): its mu panel is bisected (children inherit its azimuth count),
//     or its azimuth count doubled. Both estimates are those of the coarser rule, so the
//     reported error bounds the returned (finer) value conservatively for smooth integrands.
//   - Ideal specular (delta) parts are added analytically: Model::delta_reflectance(p, cos theta_s).
//   - Grazing sun (from 70 deg): the converged (mu, dphi) rule is cross-checked with the mirror-polar
//     rule below, unless the model declares no lobe about the mirror direction
//     (ModelDescription::mirror_lobe; tests/albedo/mirror_lobe_test.cpp checks the claim).
//   - Sharp lobes: if this (mu, dphi) rule has not converged within max_geometries / 4, black_sky()
//     integrates again in polar coordinates (rho, psi) about the mirror direction (see
//     black_sky_mirror_polar) and returns the result with the smaller error estimate. (With the shared
//     azimuth counts the (mu, dphi) rule itself converges for GGX roughness >= 0.002 in < 90k
//     geometries; the mirror-polar rule needs 2-6 times fewer.)
//   - White-sky: outer 15-point Gauss-Kronrod panels in mu_i (adaptive, same |K15 - G7| estimate) of
//     inner integrals, node j computed to tolerance tol/(4 mu_j) (their weighted sum adds <= tol/2).
//     Isotropic models that pass a reciprocity check (f(w_i, w_r) = f(w_r, w_i) to 1e-10 relative at
//     24 scattered geometry pairs, every parameter set): the inner integral runs over mu_r in [0, mu_i]
//     only and counts twice (plus half the ideal specular part);
//     grazing mu_i, where lobes at the horizon made full black-sky integrals costly, then cover a thin
//     band only, and Oren-Nayar's kink at theta_r = theta_i is on the boundary. Otherwise the inner
//     integral is the black-sky albedo; for anisotropic models first averaged over the sun azimuth
//     with an adaptive periodic trapezoid.
//   - Known limits: the white-sky triangle rule has no mirror-polar fallback (converged = false is
//     reported if its budget runs out).
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

#include "roadbrdf/models/model.h"

namespace roadbrdf::albedo {

struct QuadratureSettings {
  double tolerance = 1e-5;               // absolute, on every parameter set (wavelength)
  std::size_t max_geometries = 400'000;  // safety stop per black-sky integral (each geometry covers all sets)
  // black_sky() from a sun zenith of 70 deg: cross-check the (mu, dphi) rule with the mirror-polar rule
  // (a narrow lobe may fall between its first nodes). False only where the caller knows the (mu, dphi)
  // rule resolves the integrand: the gradient of a black-sky integral whose value passed the check
  // (gradient_integrals.h).
  bool grazing_check = true;
  // The first `steering_sets` parameter sets are held to `tolerance`, the others (followers) to
  // `follower_factor` times it (infinity: they only follow, integrated on the nodes the first choose,
  // their error estimates reported but not controlled; gradient_integrals.h integrates a gradient on
  // the nodes of its value integral). Only the first decide between rules (black_sky()).
  std::size_t steering_sets = std::numeric_limits<std::size_t>::max();
  double follower_factor = std::numeric_limits<double>::infinity();
  std::size_t steering(std::size_t n_sets) const { return std::min(n_sets, steering_sets); }
  // The set whose summed error estimate total[s] exceeds its tolerance by the largest ratio, or n if
  // none exceeds it.
  std::size_t worst_set(const double* total, std::size_t n) const {
    const std::size_t steer = steering(n);
    std::size_t worst = n;
    double largest = 1.0;
    for (std::size_t s = 0; s < n; ++s) {
      const double ratio = s < steer ? total[s] / tolerance : total[s] / (follower_factor * tolerance);
      if (ratio > largest) {
        largest = ratio;
        worst = s;
      }
    }
    return worst;
  }
};

// One integral for n parameter sets (e.g. one per wavelength).
struct SpectralIntegral {
  std::vector<double> value;   // per parameter set
  std::vector<double> error;   // error estimate per parameter set (absolute)
  bool converged = true;       // false if max_geometries stopped the refinement first
  std::size_t geometries = 0;  // distinct BRDF geometries evaluated (each for all parameter sets)
  // black_sky() at grazing incidence (QuadratureSettings::grazing_check): the mirror-polar rule ran and
  // agreed with the converged (mu, dphi) rule at every set, so no lobe was missed. False otherwise
  // (no check made, none needed for a model without a mirror lobe, a disagreement, the fallback, or
  // another source of the integral).
  bool lobes_checked = false;
  double max_error() const;
  // The largest error estimate of the first `n` sets.
  double max_error(std::size_t n) const;
};

// Whether the model declares itself azimuthally isotropic at every parameter set (its metadata:
// ModelDescription::isotropic, isotropic_when_equal). `params`: n_sets x parameter_count(), row-major.
bool is_isotropic(const Model& model, const double* params, std::size_t n_sets);

// Whether black_sky() cross-checks its (mu, dphi) rule with the mirror-polar rule at sun zenith
// theta_s [rad]: from 70 deg, for a model that may have a lobe about the mirror direction
// (ModelDescription::mirror_lobe), unless `settings` turn the check off.
bool grazing_check_applies(const Model& model, double theta_s, const QuadratureSettings& settings);

// Black-sky albedo at sun zenith theta_s and azimuth phi_s [rad] (phi_s matters only for anisotropic
// models). theta_s must be in [0, pi/2).
SpectralIntegral black_sky(const Model& model, const double* params, std::size_t n_sets, double theta_s,
                           double phi_s = 0.0, const QuadratureSettings& settings = {});

// Black-sky albedo averaged over the sun azimuth (1/2pi) int alpha_bs(theta_s, phi_s) dphi_s; equal to
// black_sky() for isotropic models.
SpectralIntegral black_sky_azimuth_mean(const Model& model, const double* params, std::size_t n_sets, double theta_s,
                                        const QuadratureSettings& settings = {});

// White-sky albedo.
SpectralIntegral white_sky(const Model& model, const double* params, std::size_t n_sets,
                           const QuadratureSettings& settings = {});

// Non-adaptive black-sky rule, for convergence studies: `mu_panels` equal K15 panels on each side of
// the specular mu (G7 sub-rule unused) times the transformed trapezoid with `phi_intervals` intervals
// on each azimuth quarter. No error estimate (error = 0, converged = false).
SpectralIntegral black_sky_fixed(const Model& model, const double* params, std::size_t n_sets, double theta_s,
                                 double phi_s, int mu_panels, int phi_intervals);

// Black-sky albedo in polar coordinates (rho, psi) about the mirror direction (theta_s, phi_s + pi):
// w_r = cos(rho) m + sin(rho) (cos(psi) e1 + sin(psi) e2), rho = s rho_max(psi) with rho_max the
// horizon, s on K15 panels graded geometrically towards 0 (breakpoints 2^-13 ... 1/2, 1), psi by the
// same sin^4-transformed trapezoid as dphi. A specular lobe of width ~roughness becomes a smooth,
// nearly psi-independent peak at s = 0. black_sky() falls back to this rule when the (mu, dphi) rule
// does not converge within a quarter of max_geometries.
SpectralIntegral black_sky_mirror_polar(const Model& model, const double* params, std::size_t n_sets, double theta_s,
                                        double phi_s = 0.0, const QuadratureSettings& settings = {});
// Non-adaptive version: `s_panels` equal K15 panels inside each graded panel, `psi_intervals` per quarter.
SpectralIntegral black_sky_mirror_polar_fixed(const Model& model, const double* params, std::size_t n_sets,
                                              double theta_s, double phi_s, int s_panels, int psi_intervals);

// The 15-point Gauss-Kronrod rule on [-1, 1] with its embedded 7-point Gauss-Legendre rule (QUADPACK
// qk15 constants): nodes x[0..14] ascending, weights wk; wg[j] is the Gauss weight of node j (0 for
// the 8 Kronrod-only nodes, the odd indices 1, 3, ..., 13 are the Gauss nodes).
struct KronrodRule {
  double x[15];
  double wk[15];
  double wg[15];
};
const KronrodRule& kronrod15();

}  // namespace roadbrdf::albedo
