// Hemispherical integrals against independent references: closed forms (Lambert, Hapke with the
// tabulated exact H-function, the mirror limit of a microfacet lobe = Fresnel reflectance), the
// published MODIS kernel integrals, and an independent brute-force midpoint integral (Oren-Nayar).
#include "roadbrdf/albedo/hemisphere.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#include "roadbrdf/core/data_path.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf::albedo {
namespace {

std::vector<double> params_of(const Model& m, const std::map<std::string, double>& values) {
  return parameters_from_assignments(m.description(), values);
}

TEST(Kronrod15, ExactForPolynomials) {
  const KronrodRule& r = kronrod15();
  for (int k = 0; k <= 22; ++k) {
    double sk = 0.0, sg = 0.0;
    for (int j = 0; j < 15; ++j) {
      sk += r.wk[j] * std::pow(r.x[j], k);
      sg += r.wg[j] * std::pow(r.x[j], k);
    }
    const double exact = (k % 2 == 0) ? 2.0 / (k + 1) : 0.0;
    EXPECT_NEAR(sk, exact, 1e-14) << "K15 degree " << k;
    if (k <= 13) {
      EXPECT_NEAR(sg, exact, 1e-14) << "G7 degree " << k;
    }
  }
}

TEST(Albedo, LambertIsItsAlbedo) {
  auto m = make_model("lambert");
  const std::vector<double> p = {0.05, 0.3, 0.97};  // three parameter sets
  for (double deg : {0.0, 10.0, 45.0, 80.0, 89.0}) {
    const SpectralIntegral bs = black_sky(*m, p.data(), 3, deg * kDegree);
    for (int s = 0; s < 3; ++s) EXPECT_NEAR(bs.value[s], p[s], 1e-12) << deg;
    EXPECT_LE(bs.max_error(), 1e-12);
  }
  const SpectralIntegral ws = white_sky(*m, p.data(), 3);
  for (int s = 0; s < 3; ++s) EXPECT_NEAR(ws.value[s], p[s], 1e-12);
}

// The non-adaptive rule of convergence studies: exact for a Lambertian (rho) with one panel, and
// converging on Oren-Nayar to the independent brute force below as the panels are refined.
double brute_force_black_sky(const Model& m, const std::vector<double>& p, double theta_i, int n);

TEST(Albedo, FixedRuleIsExactForLambertAndConvergesOnOrenNayar) {
  auto lambert = make_model("lambert");
  const std::vector<double> rho = {0.05, 0.97};
  for (double deg : {0.0, 45.0, 80.0}) {
    const SpectralIntegral bs = black_sky_fixed(*lambert, rho.data(), 2, deg * kDegree, 0.0, 1, 4);
    for (int s = 0; s < 2; ++s) EXPECT_NEAR(bs.value[s], rho[s], 1e-12) << deg;
    EXPECT_FALSE(bs.converged);  // no error estimate, as documented
    EXPECT_EQ(bs.max_error(), 0.0);
  }
  auto on = make_model("oren-nayar");
  const std::vector<double> p = params_of(*on, {{"albedo", 0.6}, {"sigma", 0.5}});
  const double reference = brute_force_black_sky(*on, p, 35.0 * kDegree, 1500);
  const double coarse = std::fabs(black_sky_fixed(*on, p.data(), 1, 35.0 * kDegree, 0.0, 1, 2).value[0] - reference);
  const double fine = std::fabs(black_sky_fixed(*on, p.data(), 1, 35.0 * kDegree, 0.0, 8, 32).value[0] - reference);
  EXPECT_LT(fine, 1e-5 + 3e-6);  // the brute force's own midpoint error is ~1e-6
  EXPECT_LE(fine, coarse);
}

// Independent brute force: midpoint rule in theta_r and phi_r (no Gauss rules, no splitting).
double brute_force_black_sky(const Model& m, const std::vector<double>& p, double theta_i, int n) {
  double sum = 0.0;
  const double dt = 0.5 * kPi / n, dp = 2.0 * kPi / (2 * n);
  for (int a = 0; a < n; ++a) {
    const double t = (a + 0.5) * dt;
    double ring = 0.0;
    for (int b = 0; b < 2 * n; ++b) {
      ring += m.evaluate(p.data(), geometry_from_radians(theta_i, 0.0, t, (b + 0.5) * dp));
    }
    sum += ring * std::cos(t) * std::sin(t);
  }
  return sum * dt * dp;
}

TEST(Albedo, OrenNayarMatchesBruteForce) {
  auto m = make_model("oren-nayar");
  const std::vector<double> p = params_of(*m, {{"albedo", 0.6}, {"sigma", 0.5}});
  for (double deg : {0.0, 35.0, 70.0}) {
    const SpectralIntegral bs = black_sky(*m, p.data(), 1, deg * kDegree);
    ASSERT_TRUE(bs.converged);
    EXPECT_LE(bs.error[0], 1e-5);
    const double reference = brute_force_black_sky(*m, p, deg * kDegree, 1500);
    // midpoint error O(h^2) ~ 1e-6 here; the quadrature's own estimate bounds the rest
    EXPECT_NEAR(bs.value[0], reference, 1e-5 + 3e-6) << deg;
  }
}

// Unpolarised Fresnel reflectance of a dielectric (independent closed form).
double fresnel(double cos_i, double n) {
  const double sin_t2 = (1.0 - cos_i * cos_i) / (n * n);
  const double cos_t = std::sqrt(1.0 - sin_t2);
  const double rs = (cos_i - n * cos_t) / (cos_i + n * cos_t);
  const double rp = (n * cos_i - cos_t) / (n * cos_i + cos_t);
  return 0.5 * (rs * rs + rp * rp);
}

// Near-mirror lobe (roughness 0.01). The convergence study uses the mirror-polar rule (polar coordinates
// about the mirror direction, geometric grading towards it), which black_sky() also falls back to.
TEST(Albedo, NearMirrorTorranceSparrowMeetsToleranceAndConverges) {
  auto m = make_model("torrance-sparrow");
  const std::vector<double> p = params_of(*m, {{"ks", 1.0}, {"roughness", 0.01}, {"ior", 1.5}});
  const double theta = 30.0 * kDegree;
  const SpectralIntegral adaptive = black_sky(*m, p.data(), 1, theta);
  std::printf("near-mirror TS: adaptive %.8f (err %.1e, %zu geometries), Fresnel %.8f\n", adaptive.value[0],
              adaptive.error[0], adaptive.geometries, fresnel(std::cos(theta), 1.5));
  ASSERT_TRUE(adaptive.converged);
  EXPECT_LE(adaptive.error[0], 1e-5);
  // Mirror limit: the directional albedo of a normalised microfacet lobe tends to F(theta_i) as the
  // roughness goes to 0 (masking ~ 1 at 30 deg); roughness 0.01 leaves a relative deficit ~1e-4.
  EXPECT_NEAR(adaptive.value[0], fresnel(std::cos(theta), 1.5), 2e-5);
  // Convergence in the quadrature order: fixed mirror-polar rules with more panels (inside each graded
  // panel) and azimuth intervals approach the adaptive value, ending within the tolerance.
  double previous = 1.0;
  for (int level = 0; level < 5; ++level) {
    const int panels = 1 << level, intervals = 4 << level;
    const SpectralIntegral fixed = black_sky_mirror_polar_fixed(*m, p.data(), 1, theta, 0.0, panels, intervals);
    const double diff = std::fabs(fixed.value[0] - adaptive.value[0]);
    std::printf("  %3d s panels x %4d psi intervals: %.8f |diff| %.2e\n", panels, intervals, fixed.value[0], diff);
    if (level >= 2) {
      EXPECT_LT(diff, previous + 1e-6);
    }
    previous = diff;
  }
  EXPECT_LT(previous, 1e-5);
  // Other sun zeniths: the adaptive rule meets the tolerance, agrees with a fixed fine rule, and is near
  // the mirror limit. GGX tails are heavy: the fraction of facet normals with tan(theta_m) > t is
  // alpha^2 / (alpha^2 + t^2), so ~1e-3 of the lobe at 60 deg and ~1e-2 at 80 deg reflects below the
  // horizon: the Fresnel comparison is made at 0 and 60 deg only (2e-3 relative).
  for (double deg : {0.0, 60.0, 80.0}) {
    const double t = deg * kDegree;
    const SpectralIntegral bs = black_sky(*m, p.data(), 1, t);
    EXPECT_TRUE(bs.converged) << deg;
    EXPECT_LE(bs.error[0], 1e-5) << deg;
    const SpectralIntegral fine = black_sky_mirror_polar_fixed(*m, p.data(), 1, t, 0.0, 16, 128);
    EXPECT_NEAR(bs.value[0], fine.value[0], 1e-5) << deg;
    if (deg < 70.0) {
      EXPECT_NEAR(bs.value[0], fresnel(std::cos(t), 1.5), 2e-3 * fresnel(std::cos(t), 1.5) + 1e-5) << deg;
    }
  }
}

// Sharp lobes: the (mu, dphi) rule and the mirror-polar rule, two independent parameterisations of
// the hemisphere, agree within their error estimates.
TEST(Albedo, SharpLobeMuPhiAndMirrorPolarAgree) {
  auto m = make_model("torrance-sparrow");
  for (double r : {0.002, 0.03}) {
    const std::vector<double> p = params_of(*m, {{"ks", 1.0}, {"roughness", r}, {"ior", 1.5}});
    for (double deg : {30.0, 85.0}) {
      const SpectralIntegral a = black_sky(*m, p.data(), 1, deg * kDegree);
      const SpectralIntegral b = black_sky_mirror_polar(*m, p.data(), 1, deg * kDegree);
      EXPECT_TRUE(a.converged && b.converged) << r << " " << deg;
      EXPECT_LE(std::max(a.error[0], b.error[0]), 1e-5) << r << " " << deg;
      EXPECT_NEAR(a.value[0], b.value[0], a.error[0] + b.error[0]) << r << " " << deg;
    }
  }
}

// The mirror-polar rule is a second, independent parameterisation of the same integral.
TEST(Albedo, MirrorPolarAgreesWithMuPhiRule) {
  auto m = make_model("oren-nayar+torrance-sparrow");
  const std::vector<double> p = params_of(*m, {{"oren-nayar.albedo", 0.3},
                                               {"oren-nayar.sigma", 0.3},
                                               {"torrance-sparrow.ks", 0.05},
                                               {"torrance-sparrow.roughness", 0.3}});
  for (double deg : {0.0, 40.0, 75.0}) {
    const SpectralIntegral a = black_sky(*m, p.data(), 1, deg * kDegree);
    const SpectralIntegral b = black_sky_mirror_polar(*m, p.data(), 1, deg * kDegree);
    EXPECT_NEAR(a.value[0], b.value[0], a.error[0] + b.error[0]) << deg;
  }
  auto l = make_model("lambert");
  const std::vector<double> q = {0.4};
  for (double deg : {0.0, 45.0, 85.0}) {
    const SpectralIntegral b = black_sky_mirror_polar(*l, q.data(), 1, deg * kDegree);
    EXPECT_NEAR(b.value[0], 0.4, 1e-5) << deg;
    EXPECT_LE(b.error[0], 1e-5) << deg;
  }
}

TEST(Albedo, WhiteSkyOfARoughDielectricLobeIsBelowOne) {
  auto m = make_model("lambert+torrance-sparrow");
  const std::vector<double> p =
      params_of(*m, {{"lambert.albedo", 0.1}, {"torrance-sparrow.ks", 0.05}, {"torrance-sparrow.roughness", 0.3}});
  const SpectralIntegral ws = white_sky(*m, p.data(), 1);
  EXPECT_LE(ws.error[0], 1e-5);
  EXPECT_GT(ws.value[0], 0.1);
  EXPECT_LT(ws.value[0], 0.15);
}

// White-sky (reciprocity-halved triangle integral) against the definition 2 int_0^1 alpha_bs(mu) mu dmu,
// evaluated independently with 16 composite K15 panels of black-sky values at a tighter tolerance.
TEST(Albedo, WhiteSkyMatchesOuterIntegralOfBlackSky) {
  auto m = make_model("oren-nayar+torrance-sparrow");
  std::vector<double> p;
  for (double r : {0.3, 0.1}) {
    const std::vector<double> q = params_of(*m, {{"oren-nayar.albedo", 0.2},
                                                 {"oren-nayar.sigma", 0.3},
                                                 {"torrance-sparrow.ks", 0.05},
                                                 {"torrance-sparrow.roughness", r},
                                                 {"torrance-sparrow.ior", 1.55}});
    p.insert(p.end(), q.begin(), q.end());
  }
  const SpectralIntegral ws = white_sky(*m, p.data(), 2);
  std::printf("ws %.8f %.8f err %.2e %.2e geometries %zu\n", ws.value[0], ws.value[1], ws.error[0], ws.error[1],
              ws.geometries);
  EXPECT_TRUE(ws.converged);
  const KronrodRule& rule = kronrod15();
  QuadratureSettings tight;
  tight.tolerance = 1e-7;
  std::vector<double> reference(2, 0.0);
  const int panels = 16;
  for (int i = 0; i < panels; ++i) {
    // panels graded towards mu = 0 (u^2 spacing), where alpha_bs varies fastest
    const double a = std::pow(static_cast<double>(i) / panels, 2), b = std::pow(static_cast<double>(i + 1) / panels, 2);
    for (int j = 0; j < 15; ++j) {
      const double mu = 0.5 * (a + b) + 0.5 * (b - a) * rule.x[j];
      const SpectralIntegral bs = black_sky(*m, p.data(), 2, std::acos(mu), 0.0, tight);
      for (int s = 0; s < 2; ++s) reference[s] += 0.5 * (b - a) * rule.wk[j] * 2.0 * mu * bs.value[s];
    }
  }
  for (int s = 0; s < 2; ++s) {
    EXPECT_LE(ws.error[s], 1e-5);
    EXPECT_NEAR(ws.value[s], reference[s], ws.error[s] + 1e-6) << s;
  }
}

// Hapke, isotropic scatterer, no opposition effect, exact H: alpha_bs(mu0) = 1 - sqrt(1 - w) H(mu0, w).
TEST(Albedo, HapkeIsotropicMatchesChandrasekharH) {
  auto m = make_model("hapke", {{"h_function", "exact"}, {"phase", "hg"}});
  std::ifstream file(data_file("third-party/hapke/chandrasekhar-h-function.csv"));
  std::string line;
  std::getline(file, line);
  int checked = 0;
  while (std::getline(file, line)) {
    std::stringstream ss(line);
    std::string a, b, c;
    std::getline(ss, a, ',');
    std::getline(ss, b, ',');
    std::getline(ss, c, ',');
    const double w = std::stod(a), mu = std::stod(b), h = std::stod(c);
    if (w >= 1.0 || mu < 0.1 || !(w == 0.3 || w == 0.7 || w == 0.9)) continue;
    if (std::fmod(mu + 1e-9, 0.2) > 1e-6) continue;  // a few zeniths per albedo
    const std::vector<double> p = params_of(*m, {{"w", w}, {"b0", 0.0}, {"xi", 0.0}});
    const SpectralIntegral bs = black_sky(*m, p.data(), 1, std::acos(mu));
    // The table has 6 significant digits (H to <= 5e-6) and the model computes H by its own quadrature:
    // allow 1.5e-5 plus the integration error estimate.
    EXPECT_NEAR(bs.value[0], 1.0 - std::sqrt(1.0 - w) * h, 1.5e-5 + bs.error[0]) << "w=" << w << " mu=" << mu;
    ++checked;
  }
  EXPECT_GE(checked, 6);
}

TEST(Albedo, RossLiWhiteSkyKernelIntegrals) {
  // MODIS ATBD constants (p. 16 of the MOD43 ATBD; Lucht et al. 2000): WSA = f_iso + 0.189184 f_vol - 1.377622 f_geo.
  auto m = make_model("ross-li");
  const std::vector<double> vol = params_of(*m, {{"f_iso", 0.0}, {"f_vol", 1.0}, {"f_geo", 0.0}});
  const std::vector<double> geo = params_of(*m, {{"f_iso", 0.0}, {"f_vol", 0.0}, {"f_geo", 1.0}});
  EXPECT_NEAR(white_sky(*m, vol.data(), 1).value[0], 0.189184, 5e-5);
  EXPECT_NEAR(white_sky(*m, geo.data(), 1).value[0], -1.377622, 1e-4);
  // Black-sky against the MODIS polynomial, a fit with errors up to ~0.015 in kernel units.
  for (double deg : {0.0, 30.0, 60.0}) {
    const double t = deg * kDegree;
    const double poly_vol = -0.007574 - 0.070987 * t * t + 0.307588 * t * t * t;
    const double poly_geo = -1.284909 - 0.166314 * t * t + 0.041840 * t * t * t;
    EXPECT_NEAR(black_sky(*m, vol.data(), 1, t).value[0], poly_vol, 0.015) << deg;
    EXPECT_NEAR(black_sky(*m, geo.data(), 1, t).value[0], poly_geo, 0.015) << deg;
  }
}

TEST(Albedo, AnisotropyDetection) {
  auto as = make_model("ashikhmin-shirley");
  std::vector<double> p = params_of(*as, {{"nu", 10.0}, {"nv", 10.0}});
  EXPECT_TRUE(is_isotropic(*as, p.data(), 1));
  p = params_of(*as, {{"nu", 10.0}, {"nv", 100.0}});
  EXPECT_FALSE(is_isotropic(*as, p.data(), 1));
  // Anisotropic Lafortune lobes are isotropic where C_x = C_y (as at the defaults), not elsewhere.
  auto composite = make_model("lambert+lafortune", {{"isotropic", "no"}});
  std::vector<double> q = composite->description().default_parameters();
  EXPECT_TRUE(is_isotropic(*composite, q.data(), 1));
  q[*composite->description().parameter_index("lafortune.cy1")] = -0.5;
  EXPECT_FALSE(is_isotropic(*composite, q.data(), 1));
  // An isotropic A-S integrated with the anisotropic machinery (azimuth mean) gives the same value.
  auto iso = make_model("ashikhmin-shirley");
  const std::vector<double> pi = params_of(*iso, {{"nu", 10.0}, {"nv", 10.0}});
  const std::vector<double> pa = params_of(*iso, {{"nu", 10.0}, {"nv", 10.000001}});
  const double a = black_sky(*iso, pi.data(), 1, 0.6).value[0];
  const double b = black_sky_azimuth_mean(*iso, pa.data(), 1, 0.6).value[0];
  EXPECT_NEAR(a, b, 2e-5);
}

TEST(Albedo, KelemenBlackSkyIsOneAtGrazingSunWithWhiteMatte) {
  // The Kelemen & Szirmay-Kalos coupling returns every photon when the matte albedo is 1: the
  // black-sky albedo is exactly 1 at every sun zenith (a physical identity of the model, checked
  // independently of the albedo module in tests/models/kelemen_test.cpp). theta = 89 deg is the CIE
  // r-table viewing angle, where a coarse specular-albedo table used to give up to 1.0042. The
  // quadrature is run to 1e-8 here so that the 1e-5 checked is the model's own accuracy (its stated
  // target), not that plus the albedo integrator's default tolerance.
  QuadratureSettings tight;
  tight.tolerance = 1e-8;
  tight.max_geometries = 4'000'000;
  for (const std::string dist : {"beckmann", "ward", "phong"}) {
    auto m = make_model("kelemen-szirmay-kalos", {{"distribution", dist}});
    for (double alpha : {0.01, 0.05, 0.3}) {
      const std::vector<double> p = params_of(*m, {{"albedo", 1.0}, {"roughness", alpha}, {"ior", 1.5}});
      for (double deg : {89.0, 89.5}) {
        const SpectralIntegral r = black_sky(*m, p.data(), 1, deg * kDegree, 0.0, tight);
        EXPECT_TRUE(r.converged) << dist << ' ' << alpha << ' ' << deg;
        EXPECT_NEAR(r.value[0], 1.0, 1e-5) << dist << ' ' << alpha << ' ' << deg;
      }
    }
  }
}

TEST(Albedo, GrazingCrossCheckSaysWhetherTheFirstRuleWasConfirmed) {
  // Below 70 deg no cross-check is made; at 80 deg a broad specular lobe (nothing to miss) passes it; a
  // check turned off is not reported as passed, nor one skipped because the model declares no lobe about
  // the mirror direction (Lambert: ModelDescription::mirror_lobe, mirror_lobe_test.cpp).
  auto m = make_model("torrance-sparrow");
  const std::vector<double> p = params_of(*m, {{"ks", 0.5}, {"roughness", 0.3}});
  ASSERT_TRUE(m->description().mirror_lobe);
  EXPECT_FALSE(black_sky(*m, p.data(), 1, 30.0 * kDegree).lobes_checked);
  EXPECT_TRUE(black_sky(*m, p.data(), 1, 80.0 * kDegree).lobes_checked);
  QuadratureSettings unchecked;
  unchecked.grazing_check = false;
  EXPECT_FALSE(black_sky(*m, p.data(), 1, 80.0 * kDegree, 0.0, unchecked).lobes_checked);
  auto lambert = make_model("lambert");
  const std::vector<double> q = {0.5};
  ASSERT_FALSE(lambert->description().mirror_lobe);
  const SpectralIntegral grazing = black_sky(*lambert, q.data(), 1, 80.0 * kDegree);
  EXPECT_FALSE(grazing.lobes_checked);
  EXPECT_NEAR(grazing.value[0], 0.5, 1e-5);
}

// The same model seen only through evaluate_batch: no preparation and no fixed-set evaluator of its
// own, so the integrators take their plainest path (the reference for their shortcuts).
class PlainModel final : public Model {
 public:
  explicit PlainModel(const Model& base) : Model(base.description()), base_(base) {}
  double evaluate(const double* p, const Geometry& g) const override { return base_.evaluate(p, g); }
  double evaluate_with_gradient(const double* p, const Geometry& g, double* gradient) const override {
    return base_.evaluate_with_gradient(p, g, gradient);
  }
  void evaluate_batch(const Geometry* g, std::size_t n, const double* p, std::size_t n_sets,
                      double* out) const override {
    base_.evaluate_batch(g, n, p, n_sets, out);
  }
  void evaluate_batch_with_gradient(const Geometry* g, std::size_t n, const double* p, double* values,
                                    double* jacobian) const override {
    base_.evaluate_batch_with_gradient(g, n, p, values, jacobian);
  }
  double delta_reflectance(const double* p, double mu) const override { return base_.delta_reflectance(p, mu); }

 private:
  const Model& base_;
};

// The mirror-polar rule evaluates Hapke's sets through the model's fixed-set evaluator (its H table
// reduced to each set's albedo, equal to evaluate_batch to rounding): the same nodes, values and error
// estimates as the rule evaluated through evaluate_batch, to rounding, for a spectrum of sets (w from
// 0.05 to 0.98 crosses every panel of the table in gamma; one set with w = 1 exactly sits on the edge)
// and with the grazing cross-check of black_sky() passing the same way.
TEST(Albedo, MirrorPolarThroughFixedSetsMatchesPlainEvaluation) {
  auto m = make_model("hapke", {{"h_function", "exact"}, {"phase", "hg"}});
  const PlainModel plain(*m);
  std::vector<double> p;
  for (int s = 0; s < 40; ++s) {
    const double w = s == 39 ? 1.0 : 0.05 + 0.93 * s / 38.0;
    const std::vector<double> q =
        params_of(*m, {{"w", w}, {"b0", 0.2 + 0.01 * s}, {"h", 0.05 + 0.002 * s}, {"xi", -0.4 + 0.02 * s}});
    p.insert(p.end(), q.begin(), q.end());
  }
  const std::size_t n = p.size() / m->parameter_count();
  // Hapke has an evaluator of its own (otherwise this would compare one path with itself).
  const std::unique_ptr<FixedSetEvaluator> own = m->fixed_sets(p.data(), n);
  const FixedSetEvaluator& evaluator = *own;
  EXPECT_NE(typeid(evaluator), typeid(FixedSetEvaluator));
  for (double deg : {20.0, 75.0, 85.0}) {
    const SpectralIntegral a = black_sky_mirror_polar(*m, p.data(), n, deg * kDegree);
    const SpectralIntegral b = black_sky_mirror_polar(plain, p.data(), n, deg * kDegree);
    EXPECT_EQ(a.geometries, b.geometries) << deg;
    EXPECT_EQ(a.converged, b.converged) << deg;
    for (std::size_t s = 0; s < n; ++s) {
      EXPECT_NEAR(a.value[s], b.value[s], 1e-13) << deg << " set " << s;
      EXPECT_NEAR(a.error[s], b.error[s], 1e-13) << deg << " set " << s;
    }
    const SpectralIntegral c = black_sky(*m, p.data(), n, deg * kDegree);
    const SpectralIntegral d = black_sky(plain, p.data(), n, deg * kDegree);
    EXPECT_EQ(c.lobes_checked, d.lobes_checked) << deg;
    for (std::size_t s = 0; s < n; ++s) EXPECT_NEAR(c.value[s], d.value[s], 1e-13) << deg << " set " << s;
  }
}

}  // namespace
}  // namespace roadbrdf::albedo
