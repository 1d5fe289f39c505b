// Torrance-Sparrow model (models/torrance_sparrow.h): closed forms at special geometries,
// reciprocity, finiteness, energy bound by independent integration, gradients vs finite differences.
#include "roadbrdf/models/torrance_sparrow.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {
namespace {

struct Combo {
  OptionSet options;
};

std::vector<OptionSet> all_valid_combos() {
  std::vector<OptionSet> out;
  for (std::string fresnel : {"exact-dielectric", "schlick", "exact-conductor", "schlick-conductor", "none"}) {
    for (std::string dist : {"ggx", "beckmann"}) {
      out.push_back(
          {{"profile", "smith"}, {"masking", "height-correlated"}, {"distribution", dist}, {"fresnel", fresnel}});
      out.push_back({{"profile", "smith"}, {"masking", "uncorrelated"}, {"distribution", dist}, {"fresnel", fresnel}});
      out.push_back({{"profile", "v-cavity"}, {"distribution", dist}, {"fresnel", fresnel}});
    }
    out.push_back({{"profile", "v-cavity"}, {"distribution", "gaussian"}, {"fresnel", fresnel}});
    out.push_back({{"profile", "smith"}, {"distribution", "beckmann"}, {"lambda", "rational"}, {"fresnel", fresnel}});
  }
  return out;
}

std::string describe_combo(const OptionSet& o) {
  std::string s;
  for (const auto& [k, v] : o) s += k + "=" + v + " ";
  return s;
}

TEST(TorranceSparrow, RegisteredWithDocumentedParameters) {
  auto m = make_model("torrance-sparrow");
  const auto& d = m->description();
  ASSERT_EQ(d.parameters.size(), 3u);
  EXPECT_EQ(d.parameters[0].name, "ks");
  EXPECT_EQ(d.parameters[1].name, "roughness");
  EXPECT_EQ(d.parameters[2].name, "ior");
  EXPECT_EQ(d.option_values.at("profile"), "smith");
  EXPECT_EQ(d.option_values.at("distribution"), "ggx");
  auto conductor = make_model("torrance-sparrow", {{"fresnel", "exact-conductor"}});
  EXPECT_EQ(conductor->description().parameters.size(), 4u);
  EXPECT_EQ(make_model("torrance-sparrow", {{"profile", "v-cavity"}, {"distribution", "gaussian"}})
                ->description()
                .parameters[1]
                .unit,
            "rad");
}

TEST(TorranceSparrow, RejectsMeaninglessOptionCombinations) {
  EXPECT_THROW(make_model("torrance-sparrow", {{"distribution", "gaussian"}}), InputError);
  EXPECT_THROW(make_model("torrance-sparrow", {{"lambda", "rational"}}), InputError);
  EXPECT_THROW(make_model("torrance-sparrow", {{"profile", "v-cavity"}, {"masking", "uncorrelated"}}), InputError);
  EXPECT_NO_THROW(make_model("torrance-sparrow", {{"distribution", "beckmann"}, {"lambda", "rational"}}));
}

TEST(TorranceSparrow, NormalIncidenceClosedForm) {
  // l = v = n: h = n, G = 1 for every profile, F = F0 = ((n-1)/(n+1))^2, D(n) = 1/(pi alpha^2)
  // (Beckmann and GGX), so f = ks F0 / (4 pi alpha^2)  (Walter 2007 eq. 20).
  const Geometry g = geometry_from_degrees(0, 0, 0, 0);
  for (std::string dist : {"ggx", "beckmann"}) {
    for (std::string profile : {"smith", "v-cavity"}) {
      auto m = make_model("torrance-sparrow", {{"distribution", dist}, {"profile", profile}});
      const double p[] = {0.7, 0.25, 1.6};
      const double f0 = std::pow(0.6 / 2.6, 2);
      EXPECT_NEAR(m->evaluate(p, g), 0.7 * f0 / (4.0 * kPi * 0.0625), 1e-12) << dist << ' ' << profile;
    }
  }
}

TEST(TorranceSparrow, MirrorGeometryClosedForm) {
  // theta_i = theta_r = t, dphi = 180 deg: h = n, l.h = cos t. Smith GGX height-correlated:
  // G = 1/(1 + 2 Lambda), Lambda = (-1 + sqrt(1 + alpha^2 tan^2 t))/2 (report eq. 3.15),
  // f = F(cos t) G / (4 pi alpha^2 cos^2 t); F exact from the s/p amplitude formulas (Hecht, Optics 4.6).
  const double alpha = 0.3, n = 1.5;
  auto m = make_model("torrance-sparrow");
  for (double deg : {10.0, 45.0, 70.0, 85.0}) {
    const double t = deg * kDegree;
    const Geometry g = geometry_from_degrees(deg, 0, deg, 180);
    const double lambda = (-1.0 + std::sqrt(1.0 + alpha * alpha * std::pow(std::tan(t), 2))) / 2.0;
    const double ct = std::cos(t);
    const double st = std::sin(t);
    const double cos_trans = std::sqrt(1.0 - st * st / (n * n));
    const double rs = std::pow((ct - n * cos_trans) / (ct + n * cos_trans), 2);
    const double rp = std::pow((n * ct - cos_trans) / (n * ct + cos_trans), 2);
    const double f = 0.5 * (rs + rp) / (1.0 + 2.0 * lambda) / (4.0 * kPi * alpha * alpha * ct * ct);
    const double p[] = {1.0, alpha, n};
    EXPECT_NEAR(m->evaluate(p, g), f, 1e-12 * f) << deg;
  }
}

TEST(TorranceSparrow, VCavityClosedForm) {
  // Cook & Torrance 1982: G = min(1, 2(n.h)(n.v)/(v.h), 2(n.h)(n.l)/(l.h)), Beckmann D (report 3.8).
  auto m = make_model("torrance-sparrow", {{"profile", "v-cavity"}, {"distribution", "beckmann"}, {"fresnel", "none"}});
  const double alpha = 0.4;
  for (auto angles :
       std::vector<std::array<double, 4>>{{30, 0, 60, 160}, {70, 0, 80, 200}, {10, 0, 85, 90}, {60, 0, 60, 0}}) {
    const Geometry g = geometry_from_degrees(angles[0], angles[1], angles[2], angles[3]);
    const Vec3 h = normalize(g.wi + g.wr);
    const double nh = h.z, lh = dot(g.wi, h), vh = dot(g.wr, h);
    const double G = std::fmin(1.0, std::fmin(2 * nh * g.wr.z / vh, 2 * nh * g.wi.z / lh));
    const double tan2 = (1 - nh * nh) / (nh * nh);
    const double D = std::exp(-tan2 / (alpha * alpha)) / (kPi * alpha * alpha * std::pow(nh, 4));
    const double f = D * G / (4 * g.wi.z * g.wr.z);
    const double p[] = {1.0, alpha};
    EXPECT_NEAR(m->evaluate(p, g), f, 1e-12 * f);
  }
}

TEST(TorranceSparrow, CookTorranceAliasIsThe1982Model) {
  // Cook & Torrance, ACM TOG 1(1) 1982, written out from the paper: R_s = F D G / (pi (N.L)(N.V)) with
  // D = exp(-(tan a / m)^2) / (m^2 cos^4 a) (eq. 4, not normalised), G as in eq. 3 and the unpolarised
  // Fresnel factor F = (g-c)^2/(2 (g+c)^2) [1 + (c(g+c)-1)^2/(c(g-c)+1)^2], c = V.H, g^2 = n^2 + c^2 - 1.
  // The alias's k_s is 4 s (torrance_sparrow.h), so k_s = 0.4 is the paper's s = 0.1.
  auto m = make_model("cook-torrance");
  const auto& d = m->description();
  EXPECT_EQ(d.name, "cook-torrance");
  EXPECT_EQ(d.option_values.at("profile"), "v-cavity");
  EXPECT_EQ(d.option_values.at("distribution"), "beckmann");
  EXPECT_EQ(d.option_values.at("fresnel"), "exact-dielectric");
  const double s = 0.1, rms_slope = 0.3, n = 1.6;
  for (auto angles : std::vector<std::array<double, 4>>{{30, 0, 60, 160}, {50, 0, 50, 180}, {10, 0, 75, 90}}) {
    const Geometry g = geometry_from_degrees(angles[0], angles[1], angles[2], angles[3]);
    const Vec3 h = normalize(g.wi + g.wr);
    const double nh = h.z, nl = g.wi.z, nv = g.wr.z, vh = dot(g.wr, h);
    const double G = std::fmin(1.0, std::fmin(2 * nh * nv / vh, 2 * nh * nl / vh));
    const double tan_a = std::sqrt(1 - nh * nh) / nh;
    const double D = std::exp(-std::pow(tan_a / rms_slope, 2)) / (rms_slope * rms_slope * std::pow(nh, 4));
    const double c = vh, gg = std::sqrt(n * n + c * c - 1);
    const double F = 0.5 * std::pow(gg - c, 2) / std::pow(gg + c, 2) *
                     (1 + std::pow(c * (gg + c) - 1, 2) / std::pow(c * (gg - c) + 1, 2));
    const double rs = s * F * D * G / (kPi * nl * nv);
    const double p[] = {4 * s, rms_slope, n};
    EXPECT_NEAR(m->evaluate(p, g), rs, 1e-12 * rs);
  }
  // Its fixed options cannot change under the alias; the error names the model that allows it.
  try {
    make_model("cook-torrance", {{"distribution", "ggx"}});
    FAIL() << "cook-torrance with distribution=ggx accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("use model 'torrance-sparrow'"), std::string::npos) << e.what();
  }
  // Options it leaves free, and the same value as fixed (how a fit file reloads it), are accepted.
  EXPECT_NO_THROW(make_model("cook-torrance", {{"distribution", "beckmann"}, {"lambda", "exact"}}));
  // In a composite: the component is named after the alias.
  auto composite = make_model("lambert+cook-torrance");
  EXPECT_NE(composite->description().parameter_index("cook-torrance.roughness"), std::nullopt);
  EXPECT_THROW(make_model("lambert+cook-torrance", {{"distribution", "ggx"}}), InputError);
  bool listed = false;
  for (const auto& alias : model_aliases())
    listed = listed || (alias.name == "cook-torrance" && alias.model == "torrance-sparrow");
  EXPECT_TRUE(listed);
}

TEST(TorranceSparrow, FiniteAndReciprocalEverywhere) {
  std::vector<Geometry> geometries = {
      geometry_from_degrees(0, 0, 0, 0),     geometry_from_degrees(89.9, 0, 89.9, 180),
      geometry_from_degrees(90, 0, 90, 180), geometry_from_degrees(90, 0, 30, 180),
      geometry_from_degrees(30, 0, 90, 180), geometry_from_degrees(90, 0, 90, 0),
      geometry_from_degrees(90, 0, 90, 90),  geometry_from_degrees(45, 0, 45, 180),
      geometry_from_degrees(45, 10, 45, 10), geometry_from_degrees(89.9, 0, 89.9, 0),
      geometry_from_degrees(60, 0, 1, 33),   geometry_from_degrees(0, 0, 89.9, 0),
  };
  for (const auto& o : all_valid_combos()) {
    auto m = make_model("torrance-sparrow", o);
    const auto& d = m->description();
    for (double rough : {d.parameters[1].lower, 0.3, d.parameters[1].upper}) {
      std::vector<double> p = d.default_parameters();
      p[1] = rough;
      for (const auto& g : geometries) {
        const double f = m->evaluate(p.data(), g);
        EXPECT_TRUE(std::isfinite(f)) << describe_combo(o) << rough;
        EXPECT_GE(f, 0.0);
        const double fs = m->evaluate(p.data(), g.swapped());
        EXPECT_NEAR(f, fs, 1e-12 * (1.0 + std::fabs(f))) << describe_combo(o);
        std::vector<double> grad(p.size());
        m->evaluate_with_gradient(p.data(), g, grad.data());
        for (double x : grad) EXPECT_TRUE(std::isfinite(x)) << describe_combo(o);
      }
    }
  }
}

// Directional albedo int f cos theta_r dw_r, integrated in half-vector space (dw_r = 4 (l.h) dw_h,
// Walter 2007 eq. 14) by the test's own midpoint rule: the lobe is resolved for small roughness.
double directional_albedo(const Model& m, const double* p, double theta_i, double alpha) {
  const Vec3 l = spherical_direction(theta_i, 0.0);
  const int nt = 400, np = 240;
  // Two panels in theta_h: the lobe [0, atan(10 alpha)] and the (GGX: heavy) tail up to pi/2.
  const double t_split = std::fmin(kPi / 2, std::atan(10.0 * alpha));
  double total = 0.0;
  for (auto [t0, t1] : {std::pair{0.0, t_split}, std::pair{t_split, kPi / 2}}) {
    if (t1 <= t0) continue;
    double sum = 0.0;
    for (int a = 0; a < nt; ++a) {
      const double th = t0 + (a + 0.5) * (t1 - t0) / nt;
      for (int b = 0; b < np; ++b) {
        const double ph = (b + 0.5) * kPi / np;  // symmetric in phi: x 2
        const Vec3 h = spherical_direction(th, ph);
        const double lh = dot(l, h);
        if (lh <= 0) continue;
        const Vec3 r = 2.0 * lh * h - l;
        if (r.z <= 0) continue;
        const double tr = std::acos(std::fmin(1.0, r.z));
        const double pr = std::atan2(r.y, r.x);
        const Geometry g = geometry_from_radians(theta_i, 0.0, tr, pr);
        sum += m.evaluate(p, g) * r.z * 4.0 * lh * std::sin(th);
      }
    }
    total += 2.0 * sum * ((t1 - t0) / nt) * (kPi / np);
  }
  return total;
}

TEST(TorranceSparrow, EnergyBoundedAndMirrorLimit) {
  // F = 1, ks = 1: single scattering with Smith masking reflects at most the incident energy
  // (Heitz 2014 section 3: int G1 D <o,m> dm = cos theta_o bounds it); for a smooth surface nearly all.
  for (std::string masking : {"height-correlated", "uncorrelated"}) {
    for (std::string dist : {"ggx", "beckmann"}) {
      auto m = make_model("torrance-sparrow", {{"fresnel", "none"}, {"masking", masking}, {"distribution", dist}});
      for (double alpha : {0.02, 0.3, 0.8}) {
        const double p[] = {1.0, alpha};
        for (double deg : {0.0, 40.0, 75.0}) {
          const double a = directional_albedo(*m, p, deg * kDegree, alpha);
          EXPECT_LE(a, 1.0 + 2e-3) << masking << ' ' << dist << ' ' << alpha << ' ' << deg;
          if (alpha == 0.02 && deg < 60) {
            EXPECT_NEAR(a, 1.0, 5e-3) << masking << ' ' << dist;
          }
        }
      }
    }
  }
}

TEST(TorranceSparrow, VCavityEnergyBounded) {
  // The V-cavity G is a masking function of an actual microsurface (Heitz 2014 section 5.3), so with
  // F = 1 the single-scattering albedo cannot exceed 1 either.
  for (std::string dist : {"ggx", "beckmann", "gaussian"}) {
    auto m = make_model("torrance-sparrow", {{"fresnel", "none"}, {"profile", "v-cavity"}, {"distribution", dist}});
    for (double rough : {0.05, 0.4, 1.0}) {
      const double p[] = {1.0, rough};
      for (double deg : {0.0, 45.0, 80.0}) {
        const double a = directional_albedo(*m, p, deg * kDegree, rough);
        EXPECT_LE(a, 1.0 + 2e-3) << dist << ' ' << rough << ' ' << deg;
        EXPECT_GT(a, 0.3) << dist << ' ' << rough << ' ' << deg;
      }
    }
  }
}

TEST(TorranceSparrow, GradientMatchesFiniteDifferences) {
  const std::vector<Geometry> geometries = {geometry_from_degrees(30, 0, 50, 170),
                                            geometry_from_degrees(70, 0, 60, 120), geometry_from_degrees(10, 0, 80, 20),
                                            geometry_from_degrees(89.9, 0, 40, 180)};
  for (const auto& o : all_valid_combos()) {
    auto m = make_model("torrance-sparrow", o);
    std::vector<double> p = m->description().default_parameters();
    p[1] = 0.35;
    if (p.size() > 2 && o.count("fresnel") &&
        (o.at("fresnel") == "exact-conductor" || o.at("fresnel") == "schlick-conductor")) {
      p[2] = 0.8;
      p[3] = 3.0;
    }
    for (const auto& g : geometries) {
      std::vector<double> grad(p.size());
      const double f = m->evaluate_with_gradient(p.data(), g, grad.data());
      EXPECT_NEAR(f, m->evaluate(p.data(), g), 1e-13 * (1 + f));
      for (std::size_t k = 0; k < p.size(); ++k) {
        const double h = 1e-6 * std::fmax(1.0, std::fabs(p[k]));
        std::vector<double> hi = p, lo = p;
        hi[k] += h;
        lo[k] -= h;
        const double fd = (m->evaluate(hi.data(), g) - m->evaluate(lo.data(), g)) / (2 * h);
        EXPECT_NEAR(grad[k], fd, 1e-5 * (1.0 + std::fabs(fd))) << describe_combo(o) << " parameter " << k;
      }
    }
  }
}

TEST(TorranceSparrow, BatchEqualsSingleEvaluation) {
  auto m = make_model("torrance-sparrow");
  std::vector<Geometry> gs;
  for (int k = 0; k < 20; ++k) gs.push_back(geometry_from_degrees(4.0 * k, 0, 85 - 4.0 * k, 10.0 * k));
  const double p[] = {0.9, 0.2, 1.5, 0.5, 0.4, 1.7};  // two parameter sets
  std::vector<double> out(gs.size() * 2);
  m->evaluate_batch(gs.data(), gs.size(), p, 2, out.data());
  for (std::size_t n = 0; n < gs.size(); ++n) {
    EXPECT_EQ(out[n * 2], m->evaluate(p, gs[n]));
    EXPECT_EQ(out[n * 2 + 1], m->evaluate(p + 3, gs[n]));
  }
}

}  // namespace
}  // namespace roadbrdf
