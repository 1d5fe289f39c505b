// The grazing property check shared by the property tests of the registered models
// (model_grazing_test.cpp) and of the mixtures (mixture_properties_test.cpp): the value at exactly
// grazing directions (theta_i or theta_r = 90 deg) is the limit of the values as the direction approaches
// the horizon with the other direction held fixed, or exactly 0 where the model declares it
// (ModelDescription::grazing_zero); a divergent value is always a declared 0. The reference is the model
// itself at 90 - 1e-5, 90 - 1e-7 and 90 - 1e-9 deg: a finite limit shows as steps between them that
// shrink (by about 100 for a function linear in the angle) towards the value at 90 deg, a divergence of
// the 1/cos or tan kind as values that grow by about 100 at each step.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "models/model_variants.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/random.h"
#include "roadbrdf/models/model.h"

namespace roadbrdf::test {

constexpr double kNear = 1e-5;     // deg below the horizon
constexpr double kNearer = 1e-7;   // deg below the horizon
constexpr double kNearest = 1e-9;  // deg below the horizon (cos = 1.7e-11, above kGrazingCosine)

// A geometry (theta_i, theta_r, dphi) [deg] with phi_i = 10 deg.
inline Geometry grazing_test_geometry(double theta_i, double theta_r, double dphi) {
  return geometry_from_degrees(theta_i, 10.0, theta_r, 10.0 + dphi);
}

// The (theta_i, theta_r) pairs with at least one exactly grazing direction, and which of them
// approach the horizon: 1 = theta_i, 2 = theta_r (the other held fixed).
struct GrazingCase {
  double theta_i, theta_r;
  int approaching;
};

inline std::vector<GrazingCase> grazing_cases() {
  std::vector<GrazingCase> cases;
  for (double other : {0.0, 30.0, 60.0, 89.0, 89.999, 90.0}) {
    cases.push_back({90.0, other, 1});
    cases.push_back({other, 90.0, 2});
  }
  return cases;
}

// The check on 12 parameter sets (defaults, lower bounds, upper bounds, random inside the bounds),
// each passed through `adjust` when given (a model whose bounds admit invalid sets, e.g. all mixture
// weights 0); returns how many values were the declared 0.
inline int expect_grazing_limits_or_declared_zeros(const Model& model,
                                                   const std::function<void(std::vector<double>&)>& adjust = {}) {
  const auto at = grazing_test_geometry;
  const ModelDescription& d = model.description();
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
    if (adjust) adjust(p);
    // The model's magnitude away from grazing, the scale of "negligible".
    double reference = 1e-12;
    for (double angle : {0.0, 30.0, 60.0}) {
      for (double dphi : {0.0, 90.0, 180.0})
        reference = std::fmax(reference, std::fabs(model.evaluate(p.data(), at(angle, angle, dphi))));
    }
    for (const GrazingCase& c : grazing_cases()) {
      for (double dphi : {0.0, 45.0, 90.0, 135.0, 180.0}) {
        const double f = model.evaluate(p.data(), at(c.theta_i, c.theta_r, dphi));
        auto approach = [&](double below) {
          return c.approaching == 1 ? model.evaluate(p.data(), at(90.0 - below, c.theta_r, dphi))
                                    : model.evaluate(p.data(), at(c.theta_i, 90.0 - below, dphi));
        };
        const double near = approach(kNear), nearer = approach(kNearer), nearest = approach(kNearest);
        const std::string where = d.name + " at theta_i=" + std::to_string(c.theta_i) +
                                  " theta_r=" + std::to_string(c.theta_r) + " dphi=" + std::to_string(dphi) +
                                  " parameter set " + std::to_string(s) + " approaching " +
                                  (c.approaching == 1 ? "theta_i" : "theta_r");
        if (!std::isfinite(f)) {
          ADD_FAILURE() << where << ": not finite (" << f << ")";
          continue;
        }
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
  return declared_zeros;
}

}  // namespace roadbrdf::test
