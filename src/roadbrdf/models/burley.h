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
    return d;
  }

  explicit Burley(const OptionSet& options) : dist_(distribution_of(options)) {}

  template <typename T>
  T operator()(const T* p, const Geometry& g) const {
    const double ci = g.wi.z;
    const double cr = g.wr.z;
    const microfacet::HalfVector h = microfacet::half_vector_of(g);
    const double lh = h.valid ? h.cos_ih : 0.0;
    const T& r = p[kRoughness];

    // Diffuse (Burley 2012 eq. in section 5.3).
    const T fd90 = 0.5 + 2.0 * r * (lh * lh);
    const double mi = 1.0 - ci, mr = 1.0 - cr;
    const double mi5 = (mi * mi) * (mi * mi) * mi;
    const double mr5 = (mr * mr) * (mr * mr) * mr;
    T diffuse = p[kAlbedo] * kInvPi * (1.0 + (fd90 - 1.0) * mi5) * (1.0 + (fd90 - 1.0) * mr5);
    if (!h.valid) return diffuse;

    // Specular.
    const T alpha = r * r;
    T d(0.0);
    switch (dist_) {
      case Distribution::kGgx:
        d = microfacet::ggx_d(h.cos_h, alpha);
        break;
      case Distribution::kBerry:
        d = microfacet::berry_d(h.cos_h, alpha);
        break;
      case Distribution::kGtr:
        d = microfacet::gtr_d(h.cos_h, alpha, p[kGamma]);
        break;
    }
    const T li = microfacet::ggx_cos_lambda(ci, alpha);
    const T lr = microfacet::ggx_cos_lambda(cr, alpha);
    const T g_over_cos = microfacet::smith_g2_over_cos(ci, cr, li, lr, /*height_correlated=*/false);
    const T f = fresnel_schlick(T(lh), fresnel_f0(p[kIor]));
    return diffuse + p[kSpecular] * f * d * g_over_cos * 0.25;
  }

 private:
  Distribution dist_;
};

}  // namespace roadbrdf
