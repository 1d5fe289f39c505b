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
// too (as in Hapke 1981): with b0 = 0 the model is exactly report eq. 3.29 with N = 2
// (a_1 = legendre_b, a_2 = legendre_c); with b0 > 0 it adds the narrow SHOE peak that a two-term
// series cannot represent.
//
// Option h_function: hapke1981 (H1), hapke2002 (H2) or exact (Chandrasekhar's H for isotropic
// scattering by quadrature), see models/hapke_h_function.h. The exact H is evaluated on every path
// (single, batch, prepared, gradient) by hapke::h_tabulated (models/hapke_h_table.h): a table of
// Chebyshev interpolants of the quadrature, within 3e-14 of it for w <= 1 - 1e-5 and 2e-11 up to w = 1.
//
// Properties:
//   - reciprocal: H(mu0) H(mu) and mu0 + mu are symmetric in the two directions, B and p depend on g only.
//   - non-negative inside the bounds: B >= 0, p >= 0 (HG: p > 0 for |xi| < 1; Legendre with |b| <= 1,
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
//   - Both directions exactly grazing (mu0 = mu = 0): f diverges like 1/(mu0 + mu). The denominator is
//     floored at kMinCosineSum so that the value there is finite (and huge), continuous with the
//     neighbouring geometries; no measurement or Gauss quadrature node sits exactly there.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/parameters.h"
#include "roadbrdf/models/hapke_h_function.h"
#include "roadbrdf/models/hapke_h_table.h"

namespace roadbrdf {

struct Hapke {
  static constexpr const char* kName = "hapke";
  static constexpr int kMaxParameters = 5;
  // Parameter order: w, b0, h, then xi (phase = hg) or legendre_b, legendre_c (phase = legendre).
  enum Parameter { kW = 0, kB0 = 1, kH = 2, kXi = 3, kLegendreB = 3, kLegendreC = 4 };
  enum class Phase { kHenyeyGreenstein, kLegendre };
  enum class HFunction { kHapke1981, kHapke2002, kExact };

  static constexpr double kMinCosineSum = 1e-9;

  static std::vector<OptionInfo> options() {
    return {
        {"phase",
         "single-particle phase function p(g), g = phase angle: hg = Henyey-Greenstein with asymmetry xi "
         "(xi > 0 forward); legendre = 1 + b cos g + c P2(cos g) (b > 0 backward, Hapke 1981)",
         {"hg", "legendre"},
         "hg"},
        {"h_function",
         "Chandrasekhar H function: hapke1981 = (1+2x)/(1+2x sqrt(1-w)) (error < 4%); hapke2002 = Hapke 2002 "
         "eq. 13 (error < 1%); exact = isotropic-scattering H by quadrature of its integral representation",
         {"hapke1981", "hapke2002", "exact"},
         "exact"},
    };
  }

  static ModelDescription describe(const OptionSet& options) {
    const bool legendre = options.at("phase") == "legendre";
    ModelDescription d;
    d.summary = std::string("Hapke IMSA particulate-medium BRDF with shadow-hiding opposition effect, ") +
                (legendre ? "two-term Legendre" : "Henyey-Greenstein") + " phase function, " +
                options.at("h_function") + " H function";
    d.citation =
        "Hapke, JGR 86:3039 (1981); Hapke, Icarus 67:264 (1986) for B(g); Hapke, Icarus 157:523 (2002) eq. 13 "
        "for H2; Chandrasekhar, Radiative Transfer (1960) for H; report eqs. 3.28-3.29 with B(g), HG and g "
        "corrected (README known errors)";
    d.parameters = {
        {"w", "1", "single-scattering albedo of the particles", 0.5, 0.0, 1.0, true, false},
        {"b0", "1", "amplitude B0 of the shadow-hiding opposition peak: B(g) = B0/(1 + tan(g/2)/h)", 0.0, 0.0, 1.0,
         true, false},
        {"h", "1",
         "angular width h of the opposition peak (B = B0/2 where tan(g/2) = h; g = phase angle), set by the "
         "porosity and grain-size distribution (structural, shared across wavelengths)",
         0.05, 1e-3, 2.0, false, false},
    };
    if (legendre) {
      d.parameters.push_back({"legendre_b", "1",
                              "coefficient b of P1(cos g) in p(g) = 1 + b cos g + c P2(cos g); g = phase angle, "
                              "so b > 0 is backscattering",
                              0.0, -1.0, 1.0, true, false});
      d.parameters.push_back({"legendre_c", "1",
                              "coefficient c of P2(cos g) = (3 cos^2 g - 1)/2 in p(g); the bounds of b and c keep "
                              "p >= 0",
                              0.0, 0.0, 1.0, true, false});
    } else {
      d.parameters.push_back({"xi", "1",
                              "Henyey-Greenstein asymmetry: p(g) = (1 - xi^2)/(1 + 2 xi cos g + xi^2)^1.5, "
                              "g = phase angle; xi > 0 forward scattering, xi < 0 backscattering",
                              0.0, -0.95, 0.95, true, false});
    }
    d.reciprocal = true;
    d.energy_conserving = false;  // SHOE term, IMSA, approximate H (see the header comment)
    d.non_negative = true;
    return d;
  }

  explicit Hapke(const OptionSet& options)
      : phase_(options.at("phase") == "legendre" ? Phase::kLegendre : Phase::kHenyeyGreenstein),
        h_function_(options.at("h_function") == "hapke1981"   ? HFunction::kHapke1981
                    : options.at("h_function") == "hapke2002" ? HFunction::kHapke2002
                                                              : HFunction::kExact) {}

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

  // Two-term Legendre phase function of the phase angle g (normalised, as P1 and P2 integrate to 0).
  template <typename T>
  static T legendre(const T& b, const T& c, double cos_g) {
    return 1.0 + b * cos_g + c * (1.5 * cos_g * cos_g - 0.5);
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

  template <typename T>
  T operator()(const T* p, const Geometry& g) const {
    const double mu0 = std::fmax(0.0, g.cos_theta_i());
    const double mu = std::fmax(0.0, g.cos_theta_r());
    const double cos_g = std::fmax(-1.0, std::fmin(1.0, dot(g.wi, g.wr)));
    const T& w = p[kW];
    const T b = opposition(p[kB0], p[kH], tan_half_phase_angle(g));
    const T phase =
        phase_ == Phase::kLegendre ? legendre(p[kLegendreB], p[kLegendreC], cos_g) : henyey_greenstein(p[kXi], cos_g);
    const T multiple = h_function(mu0, w) * h_function(mu, w) - 1.0;
    const double inv_sum = 1.0 / std::fmax(mu0 + mu, kMinCosineSum);
    return w * (0.25 * kInvPi * inv_sum) * ((1.0 + b) * phase + multiple);
  }

 private:
  Phase phase_;
  HFunction h_function_;
};

}  // namespace roadbrdf
