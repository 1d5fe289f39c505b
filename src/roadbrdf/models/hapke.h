// Hapke's bidirectional reflectance of a particulate medium: isotropic multiple-scattering
// approximation (IMSA) with the shadow-hiding opposition effect (SHOE).
//
// Hapke, "Bidirectional reflectance spectroscopy 1. Theory", JGR 86(B4):3039-3054 (1981);
// opposition term as in Hapke, Icarus 67:264-280 (1986); Hapke, "Theory of Reflectance and Emittance
// Spectroscopy" (1993); H2 from Hapke, Icarus 157:523-534 (2002) eq. 13; report section 3.8,
// eqs. 3.28-3.29. Hapke's bidirectional reflectance r (radiance / collimated irradiance on a plane
// perpendicular to the beam) is
//   r = (w/4pi) mu0/(mu0 + mu) {[1 + B(g)] p(g) + H(mu0) H(mu) - 1},
// and this model returns the BRDF f = r/mu0 [sr^-1] (domain notes section 0), i.e. report eq. 3.28:
//   f = (w/4pi) 1/(mu0 + mu) {[1 + B(g)] p(g) + H(mu0) H(mu) - 1}.
// mu0 = cos(theta_i), mu = cos(theta_r); g is the phase angle between w_i and w_r (both pointing away
// from the surface): cos g = w_i . w_r = cos th_i cos th_r + sin th_i sin th_r cos(phi_r - phi_i); g = 0
// is the retro (backscatter) direction. Where the report differs from the papers, the papers win:
//   - B(g) = B0 / (1 + tan(g/2)/h) (Hapke 1986); the report prints 1/(h tan(g/2)) in the denominator.
//   - Henyey-Greenstein p(g) = (1 - xi^2)/(1 + 2 xi cos g + xi^2)^{3/2}: the report drops the 2, which
//     breaks the normalisation (1/4pi) int p dOmega = 1. With the phase angle g, xi > 0 is forward
//     scattering (peak at g = pi), xi < 0 backscattering.
//   - g is the angle between the two directions, not a difference of zenith angles.
//   - The report writes H with theta; H is a function of the cosine (mu0, mu).
//
// Option phase = legendre: p(g) = 1 + b P1(cos g) + c P2(cos g) = 1 + b cos g + c (3 cos^2 g - 1)/2, the
// two-term Legendre phase function of Hapke (1981), in the *phase-angle* convention used with it in the
// literature (e.g. Sklute et al. 2015): b > 0 is BACKscattering here (opposite sign convention to xi;
// in terms of the scattering angle Theta = pi - g, p = 1 - b cos Theta + c P2(cos Theta)).
// Reading of report eq. 3.29: it replaces [1 + B(g)] p(g) by the series 1 + sum_{n>=1} a_n P_n; the
// leading 1 then cancels the "- 1" of eq. 3.28, which is why eq. 3.29 shows sum a_n P_n + H H without
// either: it does not drop a term. Here the opposition factor [1 + B(g)] is kept in the legendre form
// too (as in Hapke 1981): with b0 = 0 the model is exactly report eq. 3.29 with N = legendre_terms
// (a_1 = legendre_b, a_2 = legendre_c, ...); with b0 > 0 it adds the narrow SHOE peak that a short
// series cannot represent.
// Bounds of b and c (reviewed against the condition p >= 0, which is what makes p a phase function):
// with x = cos g, p(x) = 1 - c/2 + b x + (3c/2) x^2 is >= 0 on [-1, 1] exactly when |b| <= 1 + c
// (the ends) and, if |b| < 3c, b^2 <= 3c (2 - c) (the interior minimum 1 - c/2 - b^2/(6c)). That
// region spans c in [-1, 2] and b in [-sqrt 3, sqrt 3] but is not a box. The default fitting box
// [-1, 1] x [0, 1] lies inside it (see "Properties"), so a default fit is always a phase function; the
// physical ranges (`fit --bounds`) are the region's extent, and a fit there may leave the region
// (p < 0 at some g: the BRDF is then negative at some geometries, which the albedo and r-table
// checks flag).
//
// Option phase = hg2: the double Henyey-Greenstein function of Hapke (2012, "Theory of Reflectance and
// Emittance Spectroscopy", 2nd ed., eq. 6.7; the form most soil and sand studies fit):
//   p(g) = (1 + c)/2 (1 - b^2)/(1 - 2b cos g + b^2)^{3/2} + (1 - c)/2 (1 - b^2)/(1 + 2b cos g + b^2)^{3/2}
//        = (1 + c)/2 HG(-b) + (1 - c)/2 HG(b)   (HG as above: xi = -b is the backward lobe),
// 0 <= b < 1 the width of both lobes, -1 <= c <= 1 the partition: c > 0 backscattering (c = 1 is
// HG(-b), c = -1 is HG(b)). Normalised for every (b, c), p > 0, and its mean cosine of the phase
// angle is <cos g> = b c (each HG(xi) has <cos g> = -xi).
//
// Option h_function: hapke1981 (H1), hapke2002 (H2) or exact (Chandrasekhar's H for isotropic
// scattering by quadrature), see models/hapke_h_function.h. The exact H is evaluated on every path
// (single, batch, prepared, gradient) by hapke::h_tabulated (models/hapke_h_table.h): a table of
// Chebyshev interpolants of the quadrature, within 3e-14 of it for w <= 1 - 1e-5 and 2e-11 up to w = 1.
//
// Option legendre_terms = N (1..8, phase = legendre only; 2 is the two-term form above): p(g) =
// 1 + sum_{n<=N} a_n P_n(cos g), a_1 = legendre_b, a_2 = legendre_c, then legendre_a3...; default box
// |a_n| <= 1/N for N != 2, which keeps p >= 0 (models/hapke_phase.h).
// Option multiple_scattering: isotropic (IMSA, the default: H(mu0) H(mu) - 1 whatever p) or anisotropic
// (phase = legendre only): Hapke's (2002) AMSA, M = P(mu0) [H(mu) - 1] + P(mu) [H(mu0) - 1] +
// P-bar [H(mu0) - 1][H(mu) - 1] with P and P-bar from the Legendre coefficients (models/hapke_phase.h);
// H stays the isotropic-scattering H, as in Hapke (2002). Reciprocal (symmetric in mu0, mu), and >= 0
// where p >= 0 (P, P-bar are averages of p).
// Option roughness = hapke1984: Hapke's (1984) macroscopic roughness, a last parameter theta_bar [rad]
// in [0, 60 deg]: f = (w/4pi) mu0e/(mu0e + mue) (S/mu0) {[1 + B] p + H(mu0e) H(mue) - 1} with the
// effective cosines and shadowing function of models/hapke_roughness.h; at theta_bar = 0 the smooth
// formula itself (bit for bit). Its gradient is the automatic derivative (dH/dx from the H table).
// Properties:
//   - reciprocal: H(mu0) H(mu) and mu0 + mu are symmetric in the two directions, B and p depend on g only
//     (roughness: (mu0e/mu0) S and mu0e + mue are symmetric, models/hapke_roughness.h).
//   - non-negative inside the bounds: B >= 0, p >= 0 (N-term Legendre: models/hapke_phase.h; roughness: S,
//     mu0e, mue > 0; HG, hg2: p > 0 for |xi| < 1, b < 1; Legendre with |b| <= 1,
//     0 <= c <= 1: at the ends cos g = +-1, p = 1 +- b + c >= c >= 0 (0 only for c = 0, |b| = 1), and an
//     interior minimum 1 - c/2 - b^2/(6c), reached when |b| < 3c, is >= 1 - 2c for c <= 1/3 and
//     >= 1 - c/2 - 1/(6c) for c >= 1/3, both >= 1/3),
//     and H >= 1 for all three H functions (H1: gamma <= 1; H2: the bracket is positive for x in (0, 1];
//     exact: ln H is an integral of -ln(1 - w a) >= 0), so the bracket is >= 0.
//   - NOT energy conserving in general: with w = 1, exact H and isotropic p the directional albedo is
//     exactly 1 (1 - sqrt(1 - w) H(mu0)), but the SHOE term [1 + B] adds single-scattered energy on top
//     (albedo > 1 for w near 1 and b0 > 0), IMSA treats multiple scattering as isotropic whatever p is,
//     and the approximate H functions do not satisfy the albedo identity (domain notes section 4: H1 and
//     H2 BRDFs integrate to 7% and 1.4% below the closed form at w = 0.95, mu0 = 0.2).
//   - Grazing directions: with one of mu0, mu = 0 every factor is finite (H(0) = 1) and the formula
//     gives its own limit. With both exactly grazing (mu0 = mu = 0) f diverges like 1/(mu0 + mu) (the
//     bracket tends to [1 + B(g)] p(g) > 0, since H(0) H(0) - 1 = 0): f is 0 there (declared in
//     grazing_zero; no irradiance and no projected area in view). Just inside, the denominator is
//     floored at kMinCosineSum so that the values stay finite (and huge).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include <ceres/jet.h>

#include "roadbrdf/core/error.h"

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/parameters.h"
#include "roadbrdf/models/hapke_h_function.h"
#include "roadbrdf/models/hapke_h_table.h"
#include "roadbrdf/models/hapke_phase.h"
#include "roadbrdf/models/hapke_roughness.h"

namespace roadbrdf {

struct Hapke {
  static constexpr const char* kName = "hapke";
  static constexpr int kMaxParameters = 3 + hapke::kMaxLegendreTerms + 1;
  // Parameter order: w, b0, h, then xi (phase = hg), legendre_b, legendre_c, legendre_a3..legendre_aN
  // (phase = legendre, N = legendre_terms) or hg2_b, hg2_c (phase = hg2), then theta_bar (roughness =
  // hapke1984).
  enum Parameter { kW = 0, kB0 = 1, kH = 2, kXi = 3, kLegendreB = 3, kLegendreC = 4, kHg2B = 3, kHg2C = 4 };
  enum class Phase { kHenyeyGreenstein, kLegendre, kDoubleHenyeyGreenstein };
  enum class HFunction { kHapke1981, kHapke2002, kExact };

  static constexpr double kMinCosineSum = 1e-9;

  static std::vector<OptionInfo> options() {
    return {
        {"phase",
         "single-particle phase function p(g), g = phase angle: hg = Henyey-Greenstein with asymmetry xi "
         "(xi > 0 forward); legendre = 1 + b cos g + c P2(cos g) (b > 0 backward, Hapke 1981); hg2 = double "
         "Henyey-Greenstein (1 + c)/2 HG(-b) + (1 - c)/2 HG(b) (c > 0 backward, Hapke 2012 eq. 6.7)",
         {"hg", "legendre", "hg2"},
         "hg"},
        {"h_function",
         "Chandrasekhar H function: hapke1981 = (1+2x)/(1+2x sqrt(1-w)) (error < 4%); hapke2002 = Hapke 2002 "
         "eq. 13 (error < 1%); exact = isotropic-scattering H by quadrature of its integral representation",
         {"hapke1981", "hapke2002", "exact"},
         "exact"},
        {"legendre_terms",
         "number N of Legendre terms of p(g) = 1 + sum_{n=1}^{N} a_n P_n(cos g) (phase = legendre only; a_1, a_2 "
         "are legendre_b, legendre_c, then legendre_a3...; for N != 2 the bounds are -1/N <= a_n <= 1/N, which keeps "
         "p >= 0, within the physical range -(2n + 1) <= a_n <= 2n + 1)",
         {"1", "2", "3", "4", "5", "6", "7", "8"},
         "2"},
        {"roughness",
         "macroscopic roughness: none = smooth surface; hapke1984 = Hapke's shadowing function S(i, e, psi) and "
         "effective cosines for a mean facet slope theta_bar (Hapke, Icarus 59:41, 1984), an added last "
         "parameter theta_bar [rad] in [0, 60 deg], default 0 = the smooth model, where its derivative is 0: a fit "
         "of it needs a `start` above 0 or several starts",
         {"none", "hapke1984"},
         "none"},
        {"multiple_scattering",
         "isotropic = IMSA, H(mu0) H(mu) - 1 whatever p; anisotropic = Hapke (2002) AMSA, P(mu0) [H(mu) - 1] + "
         "P(mu) [H(mu0) - 1] + P-bar [H(mu0) - 1][H(mu) - 1] from the Legendre coefficients (phase = legendre only)",
         {"isotropic", "anisotropic"},
         "isotropic"},
    };
  }

  static bool anisotropic_scattering(const OptionSet& options) {
    const bool anisotropic = options.at("multiple_scattering") == "anisotropic";
    if (anisotropic && options.at("phase") != "legendre") {
      throw InputError("hapke: multiple_scattering=anisotropic applies only to phase=legendre");
    }
    return anisotropic;
  }

  static int legendre_term_count(const OptionSet& options) {
    const int terms = std::stoi(options.at("legendre_terms"));  // one of the declared values
    if (terms != 2 && options.at("phase") != "legendre") {
      throw InputError("hapke: legendre_terms applies only to phase=legendre");
    }
    return terms;
  }

  static ModelDescription describe(const OptionSet& options) {
    const std::string& phase = options.at("phase");
    const int terms = legendre_term_count(options);
    const bool anisotropic = anisotropic_scattering(options);
    const std::string legendre_name = std::to_string(terms) + "-term Legendre";
    const std::string phase_name = phase == "legendre" ? legendre_name
                                   : phase == "hg2"    ? "double Henyey-Greenstein"
                                                       : "Henyey-Greenstein";
    ModelDescription d;
    d.summary = std::string("Hapke IMSA particulate-medium BRDF with shadow-hiding opposition effect, ") + phase_name +
                " phase function, " + options.at("h_function") + " H function";
    d.citation =
        "Hapke, JGR 86:3039 (1981); Hapke, Icarus 67:264 (1986) for B(g); Hapke, Icarus 157:523 (2002) eq. 13 "
        "for H2; Hapke, Theory of Reflectance and Emittance Spectroscopy, 2nd ed. (2012) eq. 6.7 for hg2; "
        "Chandrasekhar, Radiative Transfer (1960) for H; report eqs. 3.28-3.29 with B(g), HG and g corrected "
        "(docs/report-corrections.md)";
    if (anisotropic) {
      d.summary.replace(d.summary.find("IMSA"), 4, "AMSA (anisotropic multiple scattering)");
      d.citation += "; Hapke, Icarus 157:523 (2002) eqs. 23-27 for the anisotropic multiple scattering";
    }
    if (options.at("roughness") == "hapke1984") {
      d.summary += ", Hapke (1984) macroscopic roughness";
      d.citation += "; Hapke, Icarus 59:41 (1984) eqs. 46-51 for the roughness correction";
    }
    d.parameters = {
        {"w", "1", "single-scattering albedo of the particles", 0.5, 0.0, 1.0, true, false},
        {"b0", "1", "amplitude B0 of the shadow-hiding opposition peak: B(g) = B0/(1 + tan(g/2)/h)", 0.0, 0.0, 1.0,
         true, false},
        {"h", "1",
         "angular width h of the opposition peak (B = B0/2 where tan(g/2) = h; g = phase angle), set by the "
         "porosity and grain-size distribution (structural, shared across wavelengths)",
         0.05, 1e-3, 2.0, false, false},
    };
    if (phase == "legendre" && terms != 2) {
      for (int n = 1; n <= terms; ++n) {
        const auto [lower, upper] = hapke::legendre_default_bounds(terms);
        std::string what = "coefficient a_" + std::to_string(n) + " of P" + std::to_string(n) +
                           "(cos g) in p(g) = 1 + sum a_n P_n(cos g); g = phase angle";
        what += n == 1 ? ", so a_1 > 0 is backscattering" : "";
        what += "; the default bounds keep p >= 0 (sum of the absolute values <= 1)";
        d.parameters.push_back({hapke::legendre_name(n), "1", what, 0.0, lower, upper, true, false});
        d.physical_bounds[hapke::legendre_name(n)] = hapke::legendre_physical_bounds(n, terms);
      }
    } else if (phase == "legendre") {
      d.parameters.push_back({"legendre_b", "1",
                              "coefficient b of P1(cos g) in p(g) = 1 + b cos g + c P2(cos g); g = phase angle, "
                              "so b > 0 is backscattering",
                              0.0, -1.0, 1.0, true, false});
      d.parameters.push_back({"legendre_c", "1",
                              "coefficient c of P2(cos g) = (3 cos^2 g - 1)/2 in p(g); the default bounds of b "
                              "and c keep p >= 0; in the wider physical ranges p >= 0 needs |b| <= 1 + c and, "
                              "where |b| < 3c, b^2 <= 3c (2 - c)",
                              0.0, 0.0, 1.0, true, false});
      d.physical_bounds = {{"legendre_b", {-std::sqrt(3.0), std::sqrt(3.0)}}, {"legendre_c", {-1.0, 2.0}}};
    } else if (phase == "hg2") {
      d.parameters.push_back({"hg2_b", "1",
                              "width of both lobes of the double Henyey-Greenstein p(g) = (1 + c)/2 HG(-b) + "
                              "(1 - c)/2 HG(b): 0 isotropic, towards 1 narrow",
                              0.3, 0.0, 0.95, true, false});
      d.parameters.push_back({"hg2_c", "1",
                              "partition of the double Henyey-Greenstein lobes: c > 0 backscattering (1: only "
                              "the backward lobe), c < 0 forward; <cos g> = b c",
                              0.0, -1.0, 1.0, true, false});
      d.physical_bounds = {{"hg2_b", {0.0, 0.999}}};
    } else {
      d.parameters.push_back({"xi", "1",
                              "Henyey-Greenstein asymmetry: p(g) = (1 - xi^2)/(1 + 2 xi cos g + xi^2)^1.5, "
                              "g = phase angle; xi > 0 forward scattering, xi < 0 backscattering",
                              0.0, -0.95, 0.95, true, false});
    }
    if (options.at("roughness") == "hapke1984") {
      d.parameters.push_back({"theta_bar", "rad",
                              "mean slope angle of the macroscopic facets (Hapke 1984); 0 is the smooth surface, "
                              "where the derivative is 0 (start a fit away from 0)",
                              0.0, 0.0, kPi / 3.0, false, false});
    }
    d.reciprocal = true;
    d.energy_conserving = false;  // SHOE term, IMSA, approximate H (see the header comment)
    d.non_negative = true;
    // The forward lobe of the phase function (xi, hg2_b towards 1) points below the horizon; its part
    // above it near grazing sun is resolved by the (mu, dphi) rule (mirror_lobe_test, every phase option).
    d.mirror_lobe = false;
    d.grazing_zero = "where both directions are grazing (f diverges like 1/(cos theta_i + cos theta_r))";
    if (options.at("roughness") == "hapke1984") {
      d.grazing_zero =
          "where both directions are grazing (theta_bar = 0: f diverges like 1/(cos theta_i + cos theta_r); "
          "theta_bar > 0: no irradiance and no projected area in view, and S is 0/0 at psi = pi)";
    }
    return d;
  }

  explicit Hapke(const OptionSet& options)
      : phase_(options.at("phase") == "legendre" ? Phase::kLegendre
               : options.at("phase") == "hg2"    ? Phase::kDoubleHenyeyGreenstein
                                                 : Phase::kHenyeyGreenstein),
        h_function_(options.at("h_function") == "hapke1981"   ? HFunction::kHapke1981
                    : options.at("h_function") == "hapke2002" ? HFunction::kHapke2002
                                                              : HFunction::kExact),
        legendre_terms_(legendre_term_count(options)),
        roughness_(options.at("roughness") == "hapke1984"),
        anisotropic_(anisotropic_scattering(options)),
        parameter_count_(3 +
                         (phase_ == Phase::kHenyeyGreenstein ? 1
                          : phase_ == Phase::kLegendre       ? legendre_terms_
                                                             : 2) +
                         (roughness_ ? 1 : 0)) {}

  // Shadow-hiding opposition term B(g) = B0 / (1 + tan(g/2)/h) (Hapke 1986), written
  // B0 h / (h + tan(g/2)). B = B0 at g = 0, 0 at g = pi (tan(g/2) = infinity).
  template <typename T>
  static T opposition(const T& b0, const T& h, double tan_half_g) {
    if (!(tan_half_g < std::numeric_limits<double>::infinity())) return T(0.0);
    return b0 * h / (h + tan_half_g);
  }

  // tan(g/2) = |w_i - w_r| / |w_i + w_r| for unit vectors (2 sin(g/2) over 2 cos(g/2)): exact near the
  // retro direction g = 0, where B is steepest (1 - cos g would lose half the digits there).
  static double tan_half_phase_angle(const Geometry& g) {
    const double sum = length(g.wi + g.wr);
    const double difference = length(g.wi - g.wr);
    return sum > 0.0 ? difference / sum : std::numeric_limits<double>::infinity();
  }

  // Henyey-Greenstein phase function of the phase angle g (normalised: (1/4pi) int p dOmega = 1).
  template <typename T>
  static T henyey_greenstein(const T& xi, double cos_g) {
    using std::sqrt;
    const T xi2 = xi * xi;
    const T base = 1.0 + 2.0 * xi * cos_g + xi2;
    return (1.0 - xi2) / (base * sqrt(base));
  }

  // d/dxi of henyey_greenstein: -[2 xi + 3 (1 - xi^2)(cos g + xi)/D] / D^1.5, D = 1 + 2 xi cos g + xi^2.
  static double henyey_greenstein_derivative(double xi, double cos_g) {
    const double base = 1.0 + 2.0 * xi * cos_g + xi * xi;
    return -(2.0 * xi + 3.0 * (1.0 - xi * xi) * (cos_g + xi) / base) / (base * std::sqrt(base));
  }

  // Two-term Legendre phase function of the phase angle g (normalised, as P1 and P2 integrate to 0);
  // other numbers of terms: hapke::legendre_series (models/hapke_phase.h).
  template <typename T>
  static T legendre(const T& b, const T& c, double cos_g) {
    return 1.0 + b * cos_g + c * (1.5 * cos_g * cos_g - 0.5);
  }

  // Double Henyey-Greenstein phase function of the phase angle g (Hapke 2012 eq. 6.7), normalised as
  // a weighted mean of two normalised lobes.
  template <typename T>
  static T double_henyey_greenstein(const T& b, const T& c, double cos_g) {
    return 0.5 * (1.0 + c) * henyey_greenstein(T(-b), cos_g) + 0.5 * (1.0 - c) * henyey_greenstein(b, cos_g);
  }

  template <typename T>
  T phase_function(const T* p, double cos_g) const {
    switch (phase_) {
      case Phase::kLegendre:
        if (legendre_terms_ != 2) return hapke::legendre_series(p + kLegendreB, legendre_terms_, cos_g);
        return legendre(p[kLegendreB], p[kLegendreC], cos_g);
      case Phase::kDoubleHenyeyGreenstein:
        return double_henyey_greenstein(p[kHg2B], p[kHg2C], cos_g);
      case Phase::kHenyeyGreenstein:
        break;
    }
    return henyey_greenstein(p[kXi], cos_g);
  }

  int parameter_count() const { return parameter_count_; }
  int legendre_terms() const { return legendre_terms_; }
  bool rough() const { return roughness_; }

  // The multiple-scattering term of the bracket from H at the two cosines: IMSA H0 H1 - 1, or Hapke's
  // (2002) AMSA P(mu0) (H1 - 1) + P(mu) (H0 - 1) + P-bar (H0 - 1)(H1 - 1) (models/hapke_phase.h).
  template <typename T, typename X>
  T multiple_scattering(const T* p, const X& mu0, const X& mu, const T& h0, const T& h1) const {
    if (!anisotropic_) return h0 * h1 - 1.0;
    const T* a = p + kLegendreB;
    return hapke::hemisphere_average(a, legendre_terms_, mu0) * (h1 - 1.0) +
           hapke::hemisphere_average(a, legendre_terms_, mu) * (h0 - 1.0) +
           hapke::double_hemisphere_average(a, legendre_terms_) * ((h0 - 1.0) * (h1 - 1.0));
  }

  template <typename T>
  T h_function(double x, const T& w) const {
    switch (h_function_) {
      case HFunction::kHapke1981:
        return hapke::h_hapke1981(x, w);
      case HFunction::kHapke2002:
        return hapke::h_hapke2002(x, w);
      case HFunction::kExact:
        break;
    }
    return hapke::h_tabulated(x, w);  // the exact H, interpolated from a table of h_exact
  }

  // H at a cosine that depends on the parameters (the roughness option's effective cosines): for a
  // Jet, dH/dx x' is added to the derivative of h_function. dH/dx: H1 = (1 + 2x)/(1 + 2x gamma) gives
  // 2(1 - gamma)/(1 + 2x gamma)^2; H2 = 1/(1 - w x A), A = r0 + (1 - 2 r0 x) L/2, L = ln((1 + x)/x),
  // gives H2^2 w [A - r0 x L - (1 - 2 r0 x)/(2(1 + x))]; exact: the table's slope (0 below the table,
  // x < 2^-40, where H - 1 is below 1e-10).
  template <typename T>
  T h_function_at(const T& x, const T& w) const {
    if constexpr (std::is_same_v<T, double>) {
      return h_function(x, w);
    } else {
      const double xv = x.a, wv = w.a;
      double slope = 0.0;
      T value;
      if (h_function_ == HFunction::kExact && hapke::h_table_covers(xv, wv)) {
        double dh_dgamma = 0.0;
        const double gamma = std::sqrt(1.0 - wv);
        value = T(hapke::h_table_evaluate_slopes(xv, gamma, &slope, &dh_dgamma));
        value.v = (gamma > 0.0 ? -0.5 * dh_dgamma / gamma : 0.0) * w.v;
      } else {
        value = h_function(xv, w);
        const double gamma = std::sqrt(std::fmax(0.0, 1.0 - wv));
        if (h_function_ == HFunction::kHapke1981) {
          const double den = 1.0 + 2.0 * xv * gamma;
          slope = 2.0 * (1.0 - gamma) / (den * den);
        } else if (h_function_ == HFunction::kHapke2002 && xv > 0.0) {
          const double r0 = (1.0 - gamma) / (1.0 + gamma), log_term = std::log1p(1.0 / xv);
          const double a = r0 + (1.0 - 2.0 * r0 * xv) * 0.5 * log_term;
          const double h2 = value.a;
          slope = h2 * h2 * wv * (a - r0 * xv * log_term - (1.0 - 2.0 * r0 * xv) / (2.0 * (1.0 + xv)));
        }
      }
      value.v += slope * x.v;
      return value;
    }
  }

  // Geometry-only terms, computed once per geometry (model.h, "prepared geometry").
  struct Prepared {
    double mu0 = 0.0;                // cos(theta_i), >= 0
    double mu = 0.0;                 // cos(theta_r), >= 0
    double cos_g = 1.0;              // cosine of the phase angle
    double tan_half_g = 0.0;         // tan(g/2); +infinity at g = pi
    double scale = 0.0;              // 1 / (4 pi (mu0 + mu)), the sum floored at kMinCosineSum; 0 if both grazing
    hapke::RoughnessGeometry rough;  // roughness = hapke1984 only
  };

  Prepared prepare(const Geometry& g) const {
    Prepared q;
    q.mu0 = std::fmax(0.0, g.cos_theta_i());
    q.mu = std::fmax(0.0, g.cos_theta_r());
    q.cos_g = std::fmax(-1.0, std::fmin(1.0, dot(g.wi, g.wr)));
    q.tan_half_g = tan_half_phase_angle(g);
    const double inv_sum = 1.0 / std::fmax(q.mu0 + q.mu, kMinCosineSum);
    q.scale = g.grazing_i() && g.grazing_r() ? 0.0 : 0.25 * kInvPi * inv_sum;
    if (roughness_) q.rough = hapke::roughness_geometry(g.wi, g.wr);
    return q;
  }

  template <typename T>
  T operator()(const T* p, const Geometry& g) const {
    return (*this)(p, prepare(g));
  }

  template <typename T>
  T operator()(const T* p, const Prepared& g) const {
    if (roughness_ && scalar_value(p[parameter_count_ - 1]) != 0.0) return rough_value(p, g);
    const T& w = p[kW];
    const T b = opposition(p[kB0], p[kH], g.tan_half_g);
    const T phase = phase_function(p, g.cos_g);
    const T multiple = multiple_scattering(p, g.mu0, g.mu, h_function(g.mu0, w), h_function(g.mu, w));
    return w * g.scale * ((1.0 + b) * phase + multiple);
  }

  // Roughness = hapke1984 at theta_bar > 0 (models/hapke_roughness.h): f = r_R/mu0 =
  // (w/4pi) mu0e/(mu0e + mue) (S/mu0) {[1 + B(g)] p(g) + H(mu0e) H(mue) - 1}, 0 where both directions
  // are grazing (grazing_zero).
  template <typename T>
  T rough_value(const T* p, const Prepared& g) const {
    if (g.scale == 0.0) return T(0.0);
    return rough_value(p, g, hapke::rough_cosines(p[parameter_count_ - 1], g.rough));
  }

  // The same from the effective cosines and S/mu0 of the geometry.
  template <typename T>
  T rough_value(const T* p, const Prepared& g, const hapke::RoughCosines<T>& c) const {
    const T& w = p[kW];
    const T b = opposition(p[kB0], p[kH], g.tan_half_g);
    const T phase = phase_function(p, g.cos_g);
    const T multiple = multiple_scattering(p, c.mu0e, c.mue, h_function_at(c.mu0e, w), h_function_at(c.mue, w));
    return w * (0.25 * kInvPi) * (c.mu0e / (c.mu0e + c.mue)) * c.shadow_over_mu0 * ((1.0 + b) * phase + multiple);
  }

  // Terms shared by the geometries of one set (model.h, "shared terms"). H depends on the geometry
  // only through mu0 and mu, and an instrument grid has few distinct zenith angles (bench grid: 8
  // incidence and 5 view angles for 400 geometries), so H(x, w) and dH/dw are computed once per
  // distinct cosine and parameter set instead of twice per geometry.
  struct SharedTerms {
    std::vector<double> cosines;                  // distinct values of mu0 and mu, increasing
    std::vector<std::uint32_t> index_i, index_r;  // per geometry: position of its mu0 and mu in `cosines`
  };

  SharedTerms share(const Prepared* g, std::size_t n) const {
    SharedTerms s;
    s.cosines.reserve(2 * n);
    for (std::size_t k = 0; k < n; ++k) {
      s.cosines.push_back(g[k].mu0);
      s.cosines.push_back(g[k].mu);
    }
    std::sort(s.cosines.begin(), s.cosines.end());
    s.cosines.erase(std::unique(s.cosines.begin(), s.cosines.end()), s.cosines.end());
    auto position = [&s](double x) {
      return static_cast<std::uint32_t>(std::lower_bound(s.cosines.begin(), s.cosines.end(), x) - s.cosines.begin());
    };
    s.index_i.resize(n);
    s.index_r.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      s.index_i[k] = position(g[k].mu0);
      s.index_r[k] = position(g[k].mu);
    }
    return s;
  }

  // Fixed parameter sets (model.h, FixedSetEvaluator; the path tracer's one set per wavelength). With
  // the exact H, each set whose w is in the table keeps the table reduced to its albedo
  // (hapke::h_table_series), so an evaluation computes T_a(t) once per cosine for all sets and then 12
  // multiply-adds per H and set, instead of a full two-variable table evaluation per H and set. The
  // sets are stored as a structure of arrays (the series coefficient-major, series[c * n_sets + s]) so
  // that each step is one loop over the sets, which the compiler vectorises; every set's sums are
  // taken in the order of hapke::h_series_evaluate. Values equal operator() to rounding (see
  // hapke_h_table.h); other sets and cosines outside the table (e.g. exactly 0) use operator() itself.
  struct FixedSets {
    std::size_t n_sets = 0, n_params = 0;
    std::vector<double> params;            // n_sets x n_params
    std::vector<double> w, b0, h, p1, p2;  // per set: w, b0, h and the phase parameters (p2: two-parameter phases)
    std::vector<std::size_t> by_operator;  // sets evaluated by operator() (w outside the table)
    std::vector<double> series;            // hapke::kHTableSeriesSize x n_sets, coefficient-major
  };

  FixedSets fix(const double* p, std::size_t n) const {
    FixedSets f;
    f.n_sets = n;
    f.n_params = static_cast<std::size_t>(parameter_count_);
    f.params.assign(p, p + n * f.n_params);
    f.series.assign(n * hapke::kHTableSeriesSize, 0.0);
    std::vector<double> one(hapke::kHTableSeriesSize);
    for (std::size_t s = 0; s < n; ++s) {
      const double* q = f.params.data() + s * f.n_params;
      f.w.push_back(q[kW]);
      f.b0.push_back(q[kB0]);
      f.h.push_back(q[kH]);
      f.p1.push_back(q[3]);
      f.p2.push_back(f.n_params > 4 ? q[4] : 0.0);
      // Roughness (H at effective cosines that depend on theta_bar) and AMSA: operator().
      if (roughness_ || anisotropic_ || h_function_ != HFunction::kExact || !(q[kW] >= 0.0 && q[kW] <= 1.0)) {
        f.by_operator.push_back(s);
        continue;
      }
      hapke::h_table_series(std::sqrt(1.0 - q[kW]), one.data());
      for (int c = 0; c < hapke::kHTableSeriesSize; ++c) f.series[c * n + s] = one[c];
    }
    return f;
  }

  void evaluate_fixed(const FixedSets& f, const Geometry& geometry, double* out) const;

  // Values (bit for bit those of operator()) and, if `jacobian` is not null, the analytic gradient
  // jacobian[n * parameter count + k] (see the definition below).
  void evaluate_shared(const SharedTerms& s, const Prepared* g, std::size_t n, const double* p, double* values,
                       double* jacobian) const;

 private:
  // evaluate_shared for roughness = hapke1984: the effective cosines depend on theta_bar, so H is not
  // shared between geometries; values and gradient by ceres::Jet (the automatic derivative).
  void evaluate_with_jets(const SharedTerms& s, const Prepared* g, std::size_t n, const double* p, double* values,
                          double* jacobian) const;

 public:
  // Values at the geometries for one parameter set q (double, or Jets for the gradient), each passed to
  // store(k, value): operator() itself, except that at theta_bar > 0 the terms of theta_bar alone
  // (hapke::rough_slope) are computed once and those of each zenith (hapke::rough_zenith) once per
  // distinct zenith of the batch (s.cosines; a geometry whose sine differs in the last bit from the
  // first one's at that cosine gets its own, so the values are operator()'s bit for bit).
  template <typename T, typename Store>
  void evaluate_rough(const SharedTerms& s, const Prepared* g, std::size_t n, const T* q, Store&& store) const {
    if (!roughness_ || scalar_value(q[parameter_count_ - 1]) == 0.0) {
      for (std::size_t k = 0; k < n; ++k) store(k, (*this)(q, g[k]));
      return;
    }
    const hapke::RoughSlope<T> slope = hapke::rough_slope(q[parameter_count_ - 1]);
    struct Cached {
      double sin = -1.0;  // the sine the terms were computed for; -1: none yet
      hapke::RoughZenith<T> terms;
    };
    std::vector<Cached> cache(s.cosines.size());
    auto zenith = [&](std::uint32_t c, double cos_x, double sin_x, double cot_x) {
      Cached& e = cache[c];
      if (e.sin == sin_x) return e.terms;
      const hapke::RoughZenith<T> terms = hapke::rough_zenith(slope, cos_x, sin_x, cot_x);
      if (e.sin < 0.0) e = {sin_x, terms};
      return terms;
    };
    for (std::size_t k = 0; k < n; ++k) {
      const Prepared& q_k = g[k];
      if (q_k.scale == 0.0) {
        store(k, T(0.0));
        continue;
      }
      const hapke::RoughnessGeometry& r = q_k.rough;
      const hapke::RoughZenith<T> zi = zenith(s.index_i[k], r.cos_i, r.sin_i, r.cot_i);
      const hapke::RoughZenith<T> ze = zenith(s.index_r[k], r.cos_e, r.sin_e, r.cot_e);
      store(k, rough_value(q, q_k, hapke::rough_cosines(slope, zi, ze, r)));
    }
  }

 private:
  Phase phase_;
  HFunction h_function_;
  int legendre_terms_;
  bool roughness_;
  bool anisotropic_;
  int parameter_count_;
};

}  // namespace roadbrdf
