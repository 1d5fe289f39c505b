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

#include "models/model_variants.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/random.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {
namespace {

using test::all_variants;
using test::random_parameters;
using test::test_name;
using test::Variant;

constexpr double kNear = 1e-5;     // deg below the horizon
constexpr double kNearer = 1e-7;   // deg below the horizon
constexpr double kNearest = 1e-9;  // deg below the horizon (cos = 1.7e-11, above kGrazingCosine)

class GrazingModels : public testing::TestWithParam<Variant> {
 protected:
  void SetUp() override { model_ = make_model(GetParam().model, GetParam().options); }
  std::unique_ptr<Model> model_;
};

// A geometry (theta_i, theta_r, dphi) [deg] with phi_i = 10 deg.
Geometry at(double theta_i, double theta_r, double dphi) {
  return geometry_from_degrees(theta_i, 10.0, theta_r, 10.0 + dphi);
}

// The (theta_i, theta_r) pairs with at least one exactly grazing direction, and which of them
// approach the horizon: 1 = theta_i, 2 = theta_r (the other held fixed).
struct GrazingCase {
  double theta_i, theta_r;
  int approaching;
};

std::vector<GrazingCase> grazing_cases() {
  std::vector<GrazingCase> cases;
  for (double other : {0.0, 30.0, 60.0, 89.0, 89.999, 90.0}) {
    cases.push_back({90.0, other, 1});
    cases.push_back({other, 90.0, 2});
  }
  return cases;
}

TEST_P(GrazingModels, ValueAtNinetyDegreesIsTheLimitOrADeclaredZero) {
  const ModelDescription& d = model_->description();
  Rng rng(9090);
  int declared_zeros = 0;
  for (int s = 0; s < 12; ++s) {
    std::vector<double> p = s == 0 ? d.default_parameters() : random_parameters(d, rng, 0.02);
    if (s == 1) {
      for (std::size_t k = 0; k < p.size(); ++k) p[k] = d.parameters[k].lower;
    }
    if (s == 2) {
      for (std::size_t k = 0; k < p.size(); ++k) p[k] = d.parameters[k].upper;
    }
    // The model's magnitude away from grazing, the scale of "negligible".
    double reference = 1e-12;
    for (double angle : {0.0, 30.0, 60.0}) {
      for (double dphi : {0.0, 90.0, 180.0})
        reference = std::fmax(reference, std::fabs(model_->evaluate(p.data(), at(angle, angle, dphi))));
    }
    for (const GrazingCase& c : grazing_cases()) {
      for (double dphi : {0.0, 45.0, 90.0, 135.0, 180.0}) {
        const double f = model_->evaluate(p.data(), at(c.theta_i, c.theta_r, dphi));
        auto approach = [&](double below) {
          return c.approaching == 1 ? model_->evaluate(p.data(), at(90.0 - below, c.theta_r, dphi))
                                    : model_->evaluate(p.data(), at(c.theta_i, 90.0 - below, dphi));
        };
        const double near = approach(kNear), nearer = approach(kNearer), nearest = approach(kNearest);
        const std::string where = d.name + " at theta_i=" + std::to_string(c.theta_i) +
                                  " theta_r=" + std::to_string(c.theta_r) + " dphi=" + std::to_string(dphi) +
                                  " parameter set " + std::to_string(s) + " approaching " +
                                  (c.approaching == 1 ? "theta_i" : "theta_r");
        ASSERT_TRUE(std::isfinite(f)) << where;
        if (f == 0.0 && !d.grazing_zero.empty()) {  // the documented 0
          ++declared_zeros;
          continue;
        }
        // A finite limit: the steps between the three values shrink (by ~100 for a function linear in
        // the angle), or are negligible against the model's values (1e-5: rounding of the closed forms'
        // cancellations 1e-9 deg from the horizon, e.g. Oren-Nayar's tan(beta) (sin(alpha) - (2 beta/pi)^3)).
        const double step = std::fabs(near - nearer), last = std::fabs(nearer - nearest);
        const double negligible = 1e-5 * std::fmax(reference, std::fabs(nearest));
        const bool converges = last <= 0.1 * step + negligible;
        EXPECT_TRUE(converges) << where << ": the values diverge (" << near << ", " << nearer << ", " << nearest
                               << ") but the value " << f << " is not a declared 0 (grazing_zero: '" << d.grazing_zero
                               << "')";
        if (converges) {
          EXPECT_NEAR(f, nearest, 2.0 * last + 1e-6 * std::fmax(reference, std::fabs(nearest)))
              << where << ": not the limit";
        }
      }
    }
  }
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
