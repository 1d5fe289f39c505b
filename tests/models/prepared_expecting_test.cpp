// Model::prepare_expecting (models/model.h): geometries prepared for expected parameter values (the
// fitter's start, whose fixed parameters never move; Torrance-Sparrow keeps its Fresnel factor at the
// expected index) must give the same values and Jacobians, bit for bit, as plainly prepared ones, at
// the expected parameters and away from them, for every registered model and a composite. The
// Jacobian column of the index at the expected value, which Torrance-Sparrow then takes from the
// prepared geometry, is checked against central differences of the single-geometry value path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {
namespace {

std::vector<Geometry> test_geometries() {
  std::vector<Geometry> g;
  for (double ti : {0.0, 20.0, 45.0, 70.0, 88.0}) {
    for (double tr : {0.0, 15.0, 50.0, 80.0}) {
      for (double dphi : {0.0, 90.0, 180.0}) g.push_back(geometry_from_degrees(ti, 0.0, tr, dphi));
    }
  }
  return g;
}

struct Case {
  std::string model;
  OptionSet options;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  for (const std::string& name : model_names()) out.push_back({name, {}});
  out.push_back({"torrance-sparrow", {{"fresnel", "schlick"}}});
  out.push_back({"torrance-sparrow", {{"fresnel", "exact-conductor"}}});
  out.push_back({"torrance-sparrow", {{"profile", "v-cavity"}, {"distribution", "beckmann"}}});
  out.push_back({"oren-nayar+torrance-sparrow", {}});
  return out;
}

// Parameter sets to evaluate: the expected ones, and each parameter moved towards its upper bound.
std::vector<std::vector<double>> parameter_sets(const ModelDescription& d, const std::vector<double>& expected) {
  std::vector<std::vector<double>> sets{expected};
  for (std::size_t k = 0; k < expected.size(); ++k) {
    std::vector<double> p = expected;
    const double upper = std::isfinite(d.parameters[k].upper) ? d.parameters[k].upper : expected[k] + 1.0;
    p[k] = expected[k] + 0.3 * (upper - expected[k]);
    if (p[k] != expected[k]) sets.push_back(p);
  }
  return sets;
}

TEST(PreparedExpecting, SameValuesAndJacobiansAsPlainPreparation) {
  const std::vector<Geometry> geometries = test_geometries();
  const std::size_t n = geometries.size();
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.model);
    const auto model = make_model(c.model, c.options);
    ASSERT_NE(model, nullptr);
    const ModelDescription& d = model->description();
    const std::vector<double> expected = d.default_parameters();
    const std::size_t p = expected.size();
    const auto plain = model->prepare(geometries.data(), n);
    const auto hinted = model->prepare_expecting(geometries.data(), n, expected.data());
    for (const std::vector<double>& params : parameter_sets(d, expected)) {
      std::vector<double> v0(n), v1(n), g0(n), g1(n), j0(n * p), j1(n * p);
      model->evaluate_prepared(*plain, params.data(), v0.data());
      model->evaluate_prepared(*hinted, params.data(), v1.data());
      model->evaluate_prepared_with_gradient(*plain, params.data(), g0.data(), j0.data());
      model->evaluate_prepared_with_gradient(*hinted, params.data(), g1.data(), j1.data());
      for (std::size_t g = 0; g < n; ++g) {
        ASSERT_EQ(v0[g], v1[g]) << "geometry " << g;
        ASSERT_EQ(g0[g], g1[g]) << "geometry " << g;
        for (std::size_t k = 0; k < p; ++k) ASSERT_EQ(j0[g * p + k], j1[g * p + k]) << "geometry " << g << " " << k;
      }
    }
  }
}

TEST(PreparedExpecting, TorranceSparrowIndexDerivativeAtTheExpectedIndex) {
  const std::vector<Geometry> geometries = test_geometries();
  const std::size_t n = geometries.size();
  for (const std::string fresnel : {"exact-dielectric", "schlick"}) {
    SCOPED_TRACE(fresnel);
    const auto model = make_model("torrance-sparrow", {{"fresnel", fresnel}});
    const ModelDescription& d = model->description();
    std::vector<double> expected = d.default_parameters();
    const std::size_t p = expected.size(), ior = 2;
    ASSERT_EQ(d.parameters[ior].name, "ior");
    expected[1] = 0.35;  // a roughness that spreads the lobe over most test geometries
    const auto hinted = model->prepare_expecting(geometries.data(), n, expected.data());
    std::vector<double> values(n), jacobian(n * p);
    model->evaluate_prepared_with_gradient(*hinted, expected.data(), values.data(), jacobian.data());
    const double step = 1e-6;
    std::vector<double> up = expected, down = expected;
    up[ior] += step;
    down[ior] -= step;
    int checked = 0;
    for (std::size_t g = 0; g < n; ++g) {
      const double fd =
          (model->evaluate(up.data(), geometries[g]) - model->evaluate(down.data(), geometries[g])) / (2.0 * step);
      EXPECT_NEAR(jacobian[g * p + ior], fd, 1e-6 * std::fabs(fd) + 1e-10 * std::fabs(values[g])) << "geometry " << g;
      if (std::fabs(fd) > 0.0) ++checked;
    }
    EXPECT_GT(checked, static_cast<int>(n) / 2);
  }
}

}  // namespace
}  // namespace roadbrdf
