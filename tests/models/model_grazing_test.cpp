// Every registered model and option variant at exactly grazing directions (theta_i or theta_r = 90 deg):
// the value there is the limit of the values as the direction approaches the horizon with the other
// direction held fixed, or exactly 0 where the model declares it (ModelDescription::grazing_zero); a
// divergent value is always a declared 0. The reference is the model itself at 90 - 1e-5 and 90 - 1e-7
// and 90 - 1e-9 deg: a finite limit shows as steps between them that shrink (by about 100 for a
// function linear in the angle) towards the value at 90 deg, a divergence of the 1/cos or tan kind as
// values that grow by about 100 at each step.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "models/grazing_check.h"
#include "models/model_variants.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/random.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {
namespace {

using test::all_variants;
using test::test_name;
using test::Variant;

class GrazingModels : public testing::TestWithParam<Variant> {
 protected:
  void SetUp() override { model_ = make_model(GetParam().model, GetParam().options); }
  std::unique_ptr<Model> model_;
};

const auto at = test::grazing_test_geometry;

TEST_P(GrazingModels, ValueAtNinetyDegreesIsTheLimitOrADeclaredZero) {
  const ModelDescription& d = model_->description();
  const int declared_zeros = test::expect_grazing_limits_or_declared_zeros(*model_);
  // A declared zero must be used somewhere (the claim is not decoration).
  if (!d.grazing_zero.empty()) {
    EXPECT_GT(declared_zeros, 0) << d.name << ": " << d.grazing_zero;
  }
}

// The exact grazing test of Geometry: 90 deg read from a file (cos = 6.1e-17) is grazing, 89.99999 deg
// (cos = 1.7e-7) is not.
TEST(GrazingGeometry, NinetyDegreesIsGrazingAndNearbyAnglesAreNot) {
  EXPECT_TRUE(geometry_from_degrees(90.0, 0.0, 30.0, 0.0).grazing_i());
  EXPECT_FALSE(geometry_from_degrees(90.0, 0.0, 30.0, 0.0).grazing_r());
  EXPECT_TRUE(geometry_from_degrees(30.0, 0.0, 90.0, 0.0).grazing_r());
  EXPECT_FALSE(geometry_from_degrees(89.99999, 0.0, 30.0, 0.0).grazing_i());
  EXPECT_TRUE(geometry_from_radians(kPi / 2, 0.0, 0.0, 0.0).grazing_i());
}

// The values the grazing rules replace (issue report, Oren-Nayar albedo 0.05, sigma 0.1 at
// theta_i = theta_r = 90 deg, retro plane: 1.17e13 sr^-1): now 0, declared, for Oren-Nayar and Hapke.
TEST(GrazingModels, BothDirectionsGrazingIsZeroForTheDivergentClosedForms) {
  const auto on = make_model("oren-nayar");
  const double p[2] = {0.05, 0.1};
  EXPECT_EQ(on->evaluate(p, at(90.0, 90.0, 0.0)), 0.0);
  EXPECT_FALSE(on->description().grazing_zero.empty());
  // One grazing direction: the closed form's limit, finite (alpha = 90 deg, beta = theta_i; eq. 30 with
  // sin(alpha) = 1): rho/pi (C1 + cos(dphi) C2 tan(beta) + ...), here at dphi = 90 deg (cos = 0):
  // rho/pi (C1 + C3 (4 alpha beta / pi^2)^2 tan((alpha + beta)/2)) + interreflection.
  const double s2 = 0.01, rho = 0.05, alpha = kPi / 2, beta = kPi / 6;
  const double c1 = 1.0 - 0.5 * s2 / (s2 + 0.33), c3 = 0.125 * s2 / (s2 + 0.09);
  const double direct = rho / kPi * (c1 + c3 * sqr(4.0 * alpha * beta / (kPi * kPi)) * std::tan(0.5 * (alpha + beta)));
  const double inter = 0.17 * rho * rho / kPi * s2 / (s2 + 0.13);
  EXPECT_NEAR(on->evaluate(p, at(30.0, 90.0, 90.0)), direct + inter, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(AllModels, GrazingModels, testing::ValuesIn(all_variants()), test_name);

}  // namespace
}  // namespace roadbrdf
