// Burley ("Disney principled") BRDF: retro-reflective diffuse + microfacet specular.
//
// B. Burley, "Physically-Based Shading at Disney", SIGGRAPH 2012 course notes, section 5.3
// (diffuse), 5.4-5.6 and appendix B (specular D, F, G); report eq. 3.24, section 3.5.
//
//   f_d = (rho/pi) (1 + (F_D90 - 1)(1 - cos theta_i)^5) (1 + (F_D90 - 1)(1 - cos theta_r)^5),
//   F_D90 = 0.5 + 2 roughness cos^2 theta_d,  cos theta_d = l.h (angle between w_i and the half vector;
//           Burley section 5.3; domain notes section 5: perceptual roughness, not alpha).
//   f_s = specular * F(l.h) D(h) G / (4 cos theta_i cos theta_r)    (Walter 2007 eq. 20)
//   D: berry (GTR gamma = 1), ggx (GTR gamma = 2), gtr (gamma = gtr_gamma), normalised as in Burley
//      appendix B.2 (cos-weighted integral 1), with alpha = roughness^2 (Burley section 5.4).
//   G: Smith, uncorrelated, with Walter's GGX G1 (Walter 2007 eq. 34) for every D, as Burley does.
//      alpha_g = roughness^2 as in Burley's 2014 revision of the notes (addendum "specular G
//      revisited", which withdraws the 2012 section 5.6 remap alpha_g = (0.5 + roughness/2)^2; see
//      docs/report-corrections.md).
//   F: Schlick (report eq. 2.15), F0 = ((n - 1)/(n + 1))^2.
// The report writes F_D(theta'_i) with a roughness alpha_d; we follow the paper (perceptual roughness).
// The diffuse part is not energy conserving (it exceeds rho at grazing for rough surfaces and its
// albedo is not rho): describe() says so.
#pragma once

#include <string>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/parameters.h"
#include "roadbrdf/models/fresnel.h"
#include "roadbrdf/models/microfacet.h"

namespace roadbrdf {

struct Burley {
  static constexpr const char* kName = "burley";
  static constexpr int kMaxParameters = 5;
  enum Parameter { kAlbedo = 0, kRoughness = 1, kSpecular = 2, kIor = 3, kGamma = 4 };
  enum class Distribution { kBerry, kGgx, kGtr };

  static std::vector<OptionInfo> options() {
    return {{"distribution",
             "specular normal distribution: berry (GTR gamma=1), ggx (GTR gamma=2), gtr (gamma fitted)",
             {"ggx", "berry", "gtr"},
             "ggx"}};
  }
  static Distribution distribution_of(const OptionSet& o) {
    const std::string& d = o.at("distribution");
    return d == "berry" ? Distribution::kBerry : d == "gtr" ? Distribution::kGtr : Distribution::kGgx;
  }
  static ModelDescription describe(const OptionSet& options) {
    const Distribution dist = distribution_of(options);
    ModelDescription d;
    d.summary = "Burley (Disney) diffuse with retro-reflection + GGX/Berry/GTR microfacet specular";
    d.citation = "Burley, SIGGRAPH 2012 course notes, sections 5.3-5.6 and appendix B; report eq. 3.24";
    d.parameters = {
        {"albedo", "1", "diffuse albedo rho (base colour)", 0.5, 0.0, 1.0, true, true},
        {"roughness", "1",
         "perceptual roughness r in [0, 1]: microfacet alpha = r^2; also drives the diffuse retro-reflection F_D90",
         0.5, 0.02, 1.0, false, false},
        {"specular", "1", "weight of the specular lobe (multiplies F D G / (4 cos_i cos_r))", 1.0, 0.0, 1.0, true,
         true},
        {"ior", "1", "relative refractive index n of the facets; Schlick F0 = ((n-1)/(n+1))^2", 1.5, 1.0, 3.0, true,
         false},
    };
    if (dist == Distribution::kGtr) {
      d.parameters.push_back({"gtr_gamma", "1",
                              "exponent gamma of the generalised Trowbridge-Reitz distribution (1 = Berry, 2 = GGX)",
                              1.5, 0.5, 4.0, false, false});
    }
    d.energy_conserving = false;  // Burley's diffuse term is not energy conserving (by design)
    // Both directions grazing: the half vector lies in the surface (cos theta_h = 0), where D is cut off
    // while its limit from above is not; the value there is 0 (declared) rather than a diffuse term
    // without its specular part.
    d.grazing_zero = "where both directions are grazing (the half vector lies in the surface)";
    return d;
  }

  explicit Burley(const OptionSet& options) : dist_(distribution_of(options)) {}

  // Geometry-only terms (model.h, "prepared geometry").
  struct Prepared {
    double ci = 0.0, cr = 0.0;    // cos(theta_i), cos(theta_r)
    double lh = 0.0;              // w_i.h (0 where h is undefined)
    double cos_h = 1.0;           // n.h
    bool valid = false;           // h defined (not w_i = -w_r)
    bool both_grazing = false;    // theta_i = theta_r = 90 deg (grazing_zero)
    double mi5 = 0.0, mr5 = 0.0;  // (1 - cos theta_i)^5, (1 - cos theta_r)^5: the diffuse's Schlick weights
  };

  Prepared prepare(const Geometry& g) const {
    Prepared q;
    q.ci = g.wi.z;
    q.cr = g.wr.z;
    const microfacet::HalfVector h = microfacet::half_vector_of(g);
    q.valid = h.valid;
    q.both_grazing = g.grazing_i() && g.grazing_r();
    q.lh = h.valid ? h.cos_ih : 0.0;
    q.cos_h = h.cos_h;
    const double mi = 1.0 - q.ci, mr = 1.0 - q.cr;
    q.mi5 = (mi * mi) * (mi * mi) * mi;
    q.mr5 = (mr * mr) * (mr * mr) * mr;
    return q;
  }

  // Parameter-only terms (model.h, "coefficients").
  template <typename T>
  struct Coefficients {
    T roughness;
    T albedo_over_pi;  // rho / pi
    T alpha;           // microfacet roughness r^2
    T f0;              // Schlick F0 of the index
    T specular;
    T gamma;  // GTR exponent (distribution gtr)
  };

  template <typename T>
  Coefficients<T> coefficients(const T* p) const {
    Coefficients<T> k{};
    k.roughness = p[kRoughness];
    k.albedo_over_pi = p[kAlbedo] * kInvPi;
    k.alpha = p[kRoughness] * p[kRoughness];
    k.f0 = fresnel_f0(p[kIor]);
    k.specular = p[kSpecular];
    if (dist_ == Distribution::kGtr) k.gamma = p[kGamma];
    return k;
  }

  template <typename T>
  T operator()(const Coefficients<T>& k, const Prepared& g) const {
    if (g.both_grazing) return T(0.0);  // grazing_zero
    // Diffuse (Burley 2012 eq. in section 5.3).
    const T fd90 = 0.5 + 2.0 * k.roughness * (g.lh * g.lh);
    T diffuse = k.albedo_over_pi * (1.0 + (fd90 - 1.0) * g.mi5) * (1.0 + (fd90 - 1.0) * g.mr5);
    if (!g.valid) return diffuse;

    // Specular.
    T d(0.0);
    switch (dist_) {
      case Distribution::kGgx:
        d = microfacet::ggx_d(g.cos_h, k.alpha);
        break;
      case Distribution::kBerry:
        d = microfacet::berry_d(g.cos_h, k.alpha);
        break;
      case Distribution::kGtr:
        d = microfacet::gtr_d(g.cos_h, k.alpha, k.gamma);
        break;
    }
    const T li = microfacet::ggx_cos_lambda(g.ci, k.alpha);
    const T lr = microfacet::ggx_cos_lambda(g.cr, k.alpha);
    const T g_over_cos = microfacet::smith_g2_over_cos(g.ci, g.cr, li, lr, /*height_correlated=*/false);
    const T f = fresnel_schlick(T(g.lh), k.f0);
    return diffuse + k.specular * f * d * g_over_cos * 0.25;
  }

  template <typename T>
  T operator()(const T* p, const Prepared& g) const {
    return (*this)(coefficients(p), g);
  }

  template <typename T>
  T operator()(const T* p, const Geometry& g) const {
    return (*this)(p, prepare(g));
  }

 private:
  Distribution dist_;
};

}  // namespace roadbrdf
