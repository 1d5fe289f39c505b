// Hapke's isotropic multiple-scattering approximation (IMSA) with the H1 function, and a fixed
// hemispherical quadrature for white-sky albedos: the "consistent Hapke forward model" of the intimate
// mixing method (mixing.h, method "hapke"). Implemented here, inside mixing/, so that the mixing
// method does not depend on the option set of the general "hapke" model.
//
// IMSA (Hapke 1981, JGR 86:3039, eq. 16 without opposition effect and roughness; domain notes section 5):
//   r(mu0, mu, g) = (w / 4 pi) mu0 / (mu0 + mu) [p(g) + H(mu0) H(mu) - 1]
//   BRDF = r / mu0 = (w / 4 pi) [p(g) + H(mu0) H(mu) - 1] / (mu0 + mu)          [sr^-1]
// H1 (Hapke 1981): H(x) = (1 + 2x) / (1 + 2x gamma), gamma = sqrt(1 - w).
//
// White-sky (bi-hemispherical) albedo of an isotropic BRDF (depends on the relative azimuth only):
//   A_ws = (1/pi) int int f mu0 mu dOmega0 dOmega = 2 int_0^1 mu0 dmu0 int_0^1 mu dmu int_0^2pi f ddphi,
// evaluated with Gauss-Legendre in mu0 and mu (kQuadratureMu nodes on (0,1), no node at the
// horizon) and the midpoint rule in dphi on [0, pi] doubled (f(dphi) = f(-dphi)). The same rule
// integrates the IMSA BRDF in the inversion, so that forward and inverse are consistent: the
// white-sky albedo of the IMSA BRDF (isotropic p = 1) computed by this rule, A(w), is increasing in w,
// from 0 at w = 0 to about 1.014 at w = 1 (H1 overestimates H near w = 1), so every albedo in [0, 1]
// has exactly one w. Note: A(w) differs from the closed-form spherical albedo of H1 by up to ~7 %
// (domain notes section 3 "Pitfall"); the inversion deliberately uses the integral, not the closed form.
#pragma once

#include <cstddef>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/models/model.h"

namespace roadbrdf::mixing {

inline constexpr int kQuadratureMu = 24;   // Gauss-Legendre nodes in mu0 and in mu
inline constexpr int kQuadraturePhi = 24;  // midpoints in dphi on [0, pi]

// H1(x, w) (Hapke 1981).
double hapke_h1(double x, double w);

// IMSA BRDF [sr^-1] with isotropic single scattering (p = 1): (w / 4pi) H1(mu0) H1(mu) / (mu0 + mu);
// 0 where both directions are grazing (cosines at most kGrazingCosine, core/geometry.h), where it
// diverges like 1/(mu0 + mu). With one grazing direction it is its finite limit.
double imsa_isotropic_brdf(double w, double mu0, double mu);

// The fixed quadrature: geometries (phi_i = 0) and weights with A_ws = sum weight_n f(geometry_n).
struct HemisphereRule {
  std::vector<Geometry> geometries;
  std::vector<double> weights;
  std::vector<double> mu0;  // cos theta_i of each geometry
  std::vector<double> mu;   // cos theta_r of each geometry
};
const HemisphereRule& white_sky_rule();

// White-sky albedo of `model` for `n_sets` parameter sets (contiguous, parameter_count() each),
// smooth part plus the ideal specular part (2 int R(mu0) mu0 dmu0 with the same mu0 nodes).
std::vector<double> white_sky_albedo(const Model& model, const double* params, std::size_t n_sets);

// White-sky albedo of the IMSA isotropic BRDF by the same rule (see the header comment).
double imsa_white_sky_albedo(double w);

// The w in [0, 1] with imsa_white_sky_albedo(w) = albedo. Throws InputError when the albedo is not in
// [0, imsa_white_sky_albedo(1)]. Solved in gamma = sqrt(1 - w), where A is smooth (in w it has a
// square-root singularity at w = 1), by Newton's method with the analytic derivative, safeguarded by
// bisection on the bracket [0, 1]; stops when the step or the bracket is below 1e-15 in gamma.
// Accuracy: |w - w_exact| <= 1e-12 (tested against an independent bisection to 1e-15,
// tests/mixing/hapke_inversion_test.cpp); typically 4-6 iterations of a 24 x 24 node sum
// (the former plain bisection in w needed ~43).
double invert_imsa_white_sky_albedo(double albedo);

}  // namespace roadbrdf::mixing
