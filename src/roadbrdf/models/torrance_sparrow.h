// Torrance-Sparrow / Cook-Torrance microfacet specular reflector:
//   f = k_s F(theta'_i) G D(theta_h) / (4 cos theta_i cos theta_r)
// Report eq. 3.7; Walter, Marschner, Li, Torrance, EGSR 2007, eq. 20 (with D normalised so that
// int D cos dw = 1, eq. 4); Torrance & Sparrow, JOSA 57(9) 1967; Cook & Torrance, ACM TOG 1(1) 1982.
//
// Options
//   profile      v-cavity: G = min(1, 2(n.h)(n.v)/(v.h), 2(n.h)(n.l)/(l.h)) (Cook & Torrance 1982;
//                report eq. 3.3 with its G2 term corrected, docs/report-corrections.md);
//                smith: G from Lambda (report eq. 3.10; Heitz 2014 eqs. 98-99).
//   masking      height-correlated (Heitz 2014 eq. 99, report eq. 3.10) | uncorrelated (G1 G1,
//                Walter 2007 eq. 23); smith only.
//   distribution gaussian (report eq. 3.4, sigma of the facet angle in rad; v-cavity only, no closed
//                Smith Lambda exists) | beckmann (eq. 3.8) | ggx (eq. 3.14).
//   fresnel      exact-dielectric (eq. 2.14) | schlick (eq. 2.15 with F0 = ((n-1)/(n+1))^2) |
//                exact-conductor (eq. 2.14, n + ik) | schlick-conductor (eq. 2.16) | none (F = 1).
//   lambda       exact (report eq. 3.12, erf form) | rational (eq. 3.13, Walter eq. 27); Beckmann+Smith only.
// Everything is evaluated from the Geometry's vectors: no trigonometry (except the Gaussian D's acos).
#pragma once

#include <string>
#include <type_traits>
#include <vector>

#include <ceres/jet.h>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/parameters.h"
#include "roadbrdf/models/fresnel.h"
#include "roadbrdf/models/microfacet.h"

namespace roadbrdf {

struct TorranceSparrow {
  static constexpr const char* kName = "torrance-sparrow";
  static constexpr int kMaxParameters = 4;
  enum Parameter { kKs = 0, kRoughness = 1, kIor = 2, kExtinction = 3 };

  enum class Profile { kVCavity, kSmith };
  enum class Distribution { kGaussian, kBeckmann, kGgx };
  enum class Fresnel { kExactDielectric, kSchlick, kExactConductor, kSchlickConductor, kNone };

  static std::vector<OptionInfo> options() {
    return {
        {"profile",
         "microfacet profile: v-cavity (Torrance-Sparrow / Cook-Torrance G) or smith (Lambda-based G)",
         {"smith", "v-cavity"},
         "smith"},
        {"masking",
         "Smith masking-shadowing: height-correlated 1/(1+L_i+L_r) or uncorrelated G1 G1 (smith only)",
         {"height-correlated", "uncorrelated"},
         "height-correlated"},
        {"distribution",
         "normal distribution: gaussian (v-cavity only), beckmann, ggx",
         {"ggx", "beckmann", "gaussian"},
         "ggx"},
        {"fresnel",
         "Fresnel term at the local angle theta'_i",
         {"exact-dielectric", "schlick", "exact-conductor", "schlick-conductor", "none"},
         "exact-dielectric"},
        {"lambda",
         "Beckmann Smith Lambda: exact erf form or the rational approximation (beckmann+smith only)",
         {"exact", "rational"},
         "exact"},
    };
  }

  // Cook & Torrance, ACM TOG 1(1) 1982, eqs. 3-6: the v-cavity G of Torrance-Sparrow, the Beckmann
  // distribution and the exact unpolarised dielectric Fresnel factor. Their R_s = F D G / (pi (n.l)(n.v))
  // uses an unnormalised D (no 1/pi); with D normalised (int D cos = 1) it is F D G / ((n.l)(n.v)), i.e.
  // 4 times the k_s = 1 value of eq. 3.7 here: a Cook-Torrance weight s is k_s = 4 s.
  static std::vector<ModelAlias> aliases() {
    return {{"cook-torrance",
             kName,
             "Cook-Torrance 1982: torrance-sparrow with profile=v-cavity, distribution=beckmann, "
             "fresnel=exact-dielectric",
             "Cook & Torrance, ACM TOG 1(1) 1982, eqs. 3-6",
             {{"profile", "v-cavity"}, {"distribution", "beckmann"}, {"fresnel", "exact-dielectric"}}}};
  }

  struct Resolved {
    Profile profile = Profile::kSmith;
    bool height_correlated = true;
    Distribution distribution = Distribution::kGgx;
    Fresnel fresnel = Fresnel::kExactDielectric;
    bool rational_lambda = false;
  };

  // Interpret (already resolved) options; throws InputError for combinations that make no sense.
  static Resolved interpret(const OptionSet& o) {
    Resolved r;
    r.profile = o.at("profile") == "v-cavity" ? Profile::kVCavity : Profile::kSmith;
    r.height_correlated = o.at("masking") == "height-correlated";
    const std::string& d = o.at("distribution");
    r.distribution = d == "gaussian"   ? Distribution::kGaussian
                     : d == "beckmann" ? Distribution::kBeckmann
                                       : Distribution::kGgx;
    const std::string& f = o.at("fresnel");
    r.fresnel = f == "schlick"             ? Fresnel::kSchlick
                : f == "exact-conductor"   ? Fresnel::kExactConductor
                : f == "schlick-conductor" ? Fresnel::kSchlickConductor
                : f == "none"              ? Fresnel::kNone
                                           : Fresnel::kExactDielectric;
    r.rational_lambda = o.at("lambda") == "rational";
    if (r.profile == Profile::kSmith && r.distribution == Distribution::kGaussian) {
      throw InputError(
          "torrance-sparrow: distribution=gaussian has no Smith masking function; use profile=v-cavity "
          "(or distribution=beckmann, the Gaussian-slope distribution, with profile=smith)");
    }
    if (r.rational_lambda && !(r.profile == Profile::kSmith && r.distribution == Distribution::kBeckmann)) {
      throw InputError("torrance-sparrow: lambda=rational applies only to profile=smith with distribution=beckmann");
    }
    if (!r.height_correlated && r.profile != Profile::kSmith) {
      throw InputError("torrance-sparrow: masking=uncorrelated applies only to profile=smith");
    }
    return r;
  }

  static bool is_conductor(Fresnel f) { return f == Fresnel::kExactConductor || f == Fresnel::kSchlickConductor; }

  static ModelDescription describe(const OptionSet& options) {
    const Resolved r = interpret(options);
    ModelDescription d;
    d.summary = "Torrance-Sparrow / Cook-Torrance microfacet specular reflection";
    d.citation =
        "Report eq. 3.7; Walter et al., EGSR 2007, eq. 20 (Smith: Heitz, JCGT 3(2) 2014, eqs. 98-99; "
        "v-cavity: Cook & Torrance, ACM TOG 1982)";
    d.parameters.push_back(
        {"ks", "1", "specular weight k_s multiplying F G D / (4 cos_i cos_r)", 1.0, 0.0, 1.0, true, true});
    if (r.distribution == Distribution::kGaussian) {
      d.parameters.push_back({"roughness", "rad",
                              "sigma: standard deviation of the facet angle theta_m (Gaussian, report eq. 3.4)", 0.2,
                              0.002, 1.2, false, false});
    } else {
      d.parameters.push_back({"roughness", "1",
                              std::string("alpha: RMS slope of the microfacets (") +
                                  (r.distribution == Distribution::kBeckmann ? "Beckmann" : "GGX") +
                                  " width parameter, dimensionless; ~ tan of a facet angle)",
                              0.2, 0.002, 2.0, false, false});
    }
    if (r.fresnel == Fresnel::kNone) {
      // no optical constants
    } else if (is_conductor(r.fresnel)) {
      d.parameters.push_back(
          {"ior", "1", "real part n of the complex relative refractive index n + ik", 1.0, 0.02, 10.0, true, false});
      d.parameters.push_back(
          {"k", "1", "extinction coefficient k of the relative refractive index n + ik", 6.5, 0.0, 20.0, true, false});
    } else {
      d.parameters.push_back({"ior", "1",
                              "relative refractive index n of the facets (real; e.g. 1.5 for bitumen/glass)", 1.5, 1.0,
                              3.0, true, false});
    }
    d.energy_conserving = true;  // single scattering with normalised D and G <= 1, F <= 1, ks <= 1
    // Both directions grazing: G / (cos_i cos_r) diverges for the height-correlated Smith term and the
    // value there is 0 (the half vector lies in the surface or is undefined); one grazing direction
    // keeps a finite limit (G vanishes like the cosine it divides).
    d.grazing_zero = "where both directions are grazing (F D G / (4 cos_i cos_r) diverges there)";
    return d;
  }

  explicit TorranceSparrow(const OptionSet& options) : r_(interpret(options)) {}

  // The microfacet factors D and G / (cos_i cos_r) depend on the roughness alone, and the dielectric
  // Fresnel factors on the index alone. For ceres::Jet they are differentiated with one-component Jets
  // and then lifted to T by the chain rule, dF = F'(x) dx: a quarter of the derivative arithmetic of the
  // 4-parameter Jet, and the same numbers, since every Jet operation acts on each derivative component
  // separately (bit for bit with the unit seeds of ModelAdapter).
  template <typename T>
  using SingleVariable = std::conditional_t<std::is_same_v<T, double>, double, ceres::Jet<double, 1>>;

  // x as the single variable of a one-parameter function.
  template <typename T>
  static SingleVariable<T> single(const T& x) {
    if constexpr (std::is_same_v<T, double>) {
      return x;
    } else {
      return ceres::Jet<double, 1>(x.a, 0);
    }
  }

  // f(x), computed by a one-parameter function of single(x), as T.
  template <typename T>
  static T lift(const SingleVariable<T>& f, const T& x) {
    if constexpr (std::is_same_v<T, double>) {
      return f;
    } else {
      return T(f.a, f.v[0] * x.v);
    }
  }

  // Geometry-only quantities, computed once per geometry (model.h, "prepared geometry"), and the
  // dielectric Fresnel factor at an expected index (a fit that holds the index fixed evaluates the
  // same F(theta'_i, n) at every iteration and wavelength).
  struct Prepared {
    microfacet::HalfVector h;
    double ci = 0.0;                             // cos theta_i
    double cr = 0.0;                             // cos theta_r
    microfacet::GgxLambdaGeometry ggx_i, ggx_r;  // GGX Smith Lambda inputs of w_i and w_r
    double fresnel_ior = -1.0;                   // index n the next three are for (-1: none)
    double fresnel = 0.0;                        // F(theta'_i, n) in double arithmetic
    double fresnel_jet = 0.0;                    // F(theta'_i, n) in Jet arithmetic (may differ by an ulp)
    double fresnel_derivative = 0.0;             // dF/dn
  };

  Prepared prepare(const Geometry& g) const {
    Prepared q;
    q.h = microfacet::half_vector_of(g);
    q.ci = g.wi.z;
    q.cr = g.wr.z;
    q.ggx_i = microfacet::ggx_lambda_geometry(q.ci);
    q.ggx_r = microfacet::ggx_lambda_geometry(q.cr);
    return q;
  }

  // With the Fresnel factor at the expected index (real-index Fresnel options only), computed by the
  // same functions as fresnel() in both arithmetics, so that the stored numbers are its own.
  Prepared prepare(const Geometry& g, const double* expected) const {
    Prepared q = prepare(g);
    if (q.h.valid && (r_.fresnel == Fresnel::kExactDielectric || r_.fresnel == Fresnel::kSchlick)) {
      const ceres::Jet<double, 1> f = real_index_fresnel(ceres::Jet<double, 1>(expected[kIor], 0), q.h.cos_ih);
      q.fresnel_ior = expected[kIor];
      q.fresnel = real_index_fresnel(expected[kIor], q.h.cos_ih);
      q.fresnel_jet = f.a;
      q.fresnel_derivative = f.v[0];
    }
    return q;
  }

  // The real-index Fresnel factors (exact dielectric, Schlick) as functions of the index alone.
  template <typename S>
  S real_index_fresnel(const S& ior, double cos_ih) const {
    if (r_.fresnel == Fresnel::kSchlick) return fresnel_schlick(S(cos_ih), fresnel_f0(ior));
    return fresnel_dielectric_at(cos_ih, ior);
  }

  template <typename T>
  T fresnel(const T* p, const Prepared& g) const {
    switch (r_.fresnel) {
      case Fresnel::kExactDielectric:
      case Fresnel::kSchlick:
        if (scalar_value(p[kIor]) == g.fresnel_ior) {
          if constexpr (std::is_same_v<T, double>) {
            return g.fresnel;
          } else {
            return T(g.fresnel_jet, g.fresnel_derivative * p[kIor].v);
          }
        }
        return lift(real_index_fresnel(single(p[kIor]), g.h.cos_ih), p[kIor]);
      case Fresnel::kExactConductor:
        return fresnel_conductor(T(g.h.cos_ih), p[kIor], p[kExtinction]);
      case Fresnel::kSchlickConductor:
        return fresnel_schlick_conductor(T(g.h.cos_ih), p[kIor], p[kExtinction]);
      case Fresnel::kNone:
        break;
    }
    return T(1.0);
  }

  template <typename T>
  T operator()(const T* p, const Geometry& g) const {
    return (*this)(p, prepare(g));
  }

  template <typename T>
  T operator()(const T* p, const Prepared& g) const {
    const microfacet::HalfVector& h = g.h;
    if (!h.valid) return T(0.0);
    const double ci = g.ci;
    const double cr = g.cr;
    using S = SingleVariable<T>;
    const S alpha = single(p[kRoughness]);

    S d(0.0);
    switch (r_.distribution) {
      case Distribution::kGgx:
        d = microfacet::ggx_d(h.cos_h, alpha);
        break;
      case Distribution::kBeckmann:
        d = microfacet::beckmann_d(h.cos_h, alpha);
        break;
      case Distribution::kGaussian:
        d = microfacet::gaussian_d(h.cos_h, alpha);
        break;
    }

    S g_over_cos;
    if (r_.profile == Profile::kVCavity) {
      g_over_cos = S(microfacet::vcavity_g_over_cos(ci, cr, h.cos_h, h.cos_ih));
    } else {
      S li, lr;
      if (r_.distribution == Distribution::kGgx) {
        const S alpha2 = alpha * alpha;
        li = microfacet::ggx_cos_lambda_from_alpha2(g.ggx_i, alpha2);
        lr = microfacet::ggx_cos_lambda_from_alpha2(g.ggx_r, alpha2);
      } else if (r_.rational_lambda) {
        li = microfacet::beckmann_cos_lambda_rational(ci, alpha);
        lr = microfacet::beckmann_cos_lambda_rational(cr, alpha);
      } else {
        li = microfacet::beckmann_cos_lambda(ci, alpha);
        lr = microfacet::beckmann_cos_lambda(cr, alpha);
      }
      g_over_cos = microfacet::smith_g2_over_cos(ci, cr, li, lr, r_.height_correlated);
    }
    return p[kKs] * fresnel(p, g) * lift(d, p[kRoughness]) * lift(g_over_cos, p[kRoughness]) * 0.25;
  }

 private:
  Resolved r_;
};

}  // namespace roadbrdf
