// The Hapke model's shared-terms path (models/hapke.h: H once per distinct cosine, analytic gradient,
// used by every gradient path through ModelAdapter, models/model.h) against independent computations:
//   - the values, bit for bit against the value path operator()(p, prepare(g)) (the model.h contract);
//   - the gradient against automatic differentiation (ceres::Jet) of the templated operator(), an
//     independent derivative of the same formula, for both phase functions and all three H functions,
//     and against central finite differences of the value path;
//   - a set with repeated and distinct zenith angles (H shared between geometries) against the same
//     geometries evaluated one at a time, including the exact backscatter (g = 0), grazing
//     directions and the nearly forward g -> pi (both grazing, opposite azimuths).
#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/models/hapke.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {
namespace {

std::vector<Geometry> test_geometries() {
  std::vector<Geometry> g;
  for (double ti : {0.0, 10.0, 35.0, 60.0, 85.0}) {
    for (double tr : {0.0, 10.0, 35.0, 70.0, 89.5}) {
      for (double dphi : {0.0, 60.0, 180.0}) g.push_back(geometry_from_degrees(ti, 0.0, tr, dphi));
    }
  }
  g.push_back(geometry_from_degrees(90.0, 0.0, 90.0, 0.0));    // both grazing, g = 0
  g.push_back(geometry_from_degrees(0.0, 0.0, 0.0, 0.0));      // g = 0 at normal incidence
  g.push_back(geometry_from_degrees(90.0, 0.0, 90.0, 180.0));  // g -> pi
  return g;
}

struct Case {
  const char* phase;
  const char* h_function;
  std::vector<double> p;
};

class HapkeGradient : public ::testing::TestWithParam<Case> {};

TEST_P(HapkeGradient, AgreesWithAutomaticDifferentiationAndFiniteDifferences) {
  const Case& c = GetParam();
  const OptionSet options = {{"phase", c.phase}, {"h_function", c.h_function}};
  const Hapke model(resolve_options(Hapke::kName, Hapke::options(), options));
  const auto adapter = make_model("hapke", options);
  const std::size_t P = c.p.size();
  ASSERT_EQ(adapter->parameter_count(), P);
  const std::vector<Geometry> geometries = test_geometries();
  const auto prepared = adapter->prepare(geometries.data(), geometries.size());
  std::vector<double> values(geometries.size()), jacobian(geometries.size() * P), values_only(geometries.size());
  adapter->evaluate_prepared_with_gradient(*prepared, c.p.data(), values.data(), jacobian.data());
  adapter->evaluate_prepared(*prepared, c.p.data(), values_only.data());
  using Jet = ceres::Jet<double, 5>;
  for (std::size_t n = 0; n < geometries.size(); ++n) {
    const Hapke::Prepared q = model.prepare(geometries[n]);
    const double f = model(c.p.data(), q);
    EXPECT_EQ(values[n], f) << n;
    EXPECT_EQ(values_only[n], f) << n;
    // Automatic derivative of the templated formula.
    std::vector<Jet> pj(P);
    for (std::size_t k = 0; k < P; ++k) pj[k] = Jet(c.p[k], static_cast<int>(k));
    const Jet fj = model(pj.data(), q);
    EXPECT_NEAR(fj.a, f, 1e-15 * std::fabs(f)) << n;
    for (std::size_t k = 0; k < P; ++k) {
      const double ad = fj.v[static_cast<int>(k)];
      // Absolute part: at g = 0 (tan(g/2) = 0) df/dh is exactly 0 analytically, while the Jet
      // derivative of b0 h/(h + t) rounds to a few ulp of b0/h times f.
      EXPECT_NEAR(jacobian[n * P + k], ad, 1e-12 * std::fabs(ad) + 1e-13 * std::fabs(f)) << n << " " << k;
      // Central differences of the value path (step inside the bounds for every case below).
      const double step = 1e-6;
      std::vector<double> up = c.p, down = c.p;
      up[k] += step;
      down[k] -= step;
      const double fd = (model(up.data(), q) - model(down.data(), q)) / (2.0 * step);
      EXPECT_NEAR(jacobian[n * P + k], fd, 1e-6 * std::fabs(fd) + 1e-9 * std::fabs(f)) << n << " " << k;
    }
    // One geometry at a time (its own two cosines) gives the same bits as the shared set.
    std::vector<double> single(P);
    const double fs = adapter->evaluate_with_gradient(c.p.data(), geometries[n], single.data());
    EXPECT_EQ(fs, f);
    for (std::size_t k = 0; k < P; ++k) EXPECT_EQ(single[k], jacobian[n * P + k]) << n << " " << k;
  }
}

INSTANTIATE_TEST_SUITE_P(PhaseAndH, HapkeGradient,
                         ::testing::Values(Case{"hg", "exact", {0.62, 0.6, 0.08, -0.25}},
                                           Case{"hg", "hapke2002", {0.3, 0.2, 0.5, 0.4}},
                                           Case{"hg", "hapke1981", {0.95, 0.9, 0.02, -0.6}},
                                           Case{"legendre", "exact", {0.8, 0.4, 0.1, 0.3, 0.2}},
                                           Case{"legendre", "hapke2002", {0.45, 0.1, 1.2, -0.5, 0.6}}),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           return std::string(info.param.phase) + "_" + info.param.h_function;
                         });

TEST(HapkeSharedTerms, DistinctCosines) {
  // Incidence 0, 10, 35, 60, 85, 90 deg and view 0, 10, 35, 70, 89.5, 90 deg: 8 distinct cosines for
  // 78 geometries.
  const Hapke model(resolve_options(Hapke::kName, Hapke::options(), {}));
  const std::vector<Geometry> geometries = test_geometries();
  std::vector<Hapke::Prepared> q;
  for (const Geometry& g : geometries) q.push_back(model.prepare(g));
  const Hapke::SharedTerms s = model.share(q.data(), q.size());
  for (std::size_t n = 0; n < q.size(); ++n) {
    EXPECT_EQ(s.cosines[s.index_i[n]], q[n].mu0);
    EXPECT_EQ(s.cosines[s.index_r[n]], q[n].mu);
  }
  for (std::size_t c = 1; c < s.cosines.size(); ++c) EXPECT_LT(s.cosines[c - 1], s.cosines[c]);
  EXPECT_LE(s.cosines.size(), 9u);
}

}  // namespace
}  // namespace roadbrdf
