// The exact conductor Fresnel term never goes negative (Torrance-Sparrow with
// fresnel=exact-conductor, k = 0, theta_r = 90 deg gave -4.9e-17), and with k = 0 it is the
// dielectric Fresnel reflectance, written out here independently (Born & Wolf, s and p amplitudes).
#include <gtest/gtest.h>

#include <cmath>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/models/fresnel.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {
namespace {

double dielectric(double cos_i, double n) {
  const double sin_t2 = (1.0 - cos_i * cos_i) / (n * n);
  if (sin_t2 >= 1.0) return 1.0;
  const double cos_t = std::sqrt(1.0 - sin_t2);
  const double rs = (cos_i - n * cos_t) / (cos_i + n * cos_t);
  const double rp = (n * cos_i - cos_t) / (n * cos_i + cos_t);
  return 0.5 * (rs * rs + rp * rp);
}

TEST(FresnelConductorGrazing, KZeroIsTheDielectricReflectance) {
  for (double n : {1.0, 1.2, 1.5, 2.4, 3.0}) {
    for (int k = 0; k <= 1000; ++k) {
      const double cos_i = k / 1000.0;
      EXPECT_NEAR(fresnel_conductor(cos_i, n, 0.0), dielectric(cos_i, n), 1e-12) << "n " << n << " cos " << cos_i;
    }
  }
}

TEST(FresnelConductorGrazing, TorranceSparrowIsNeverNegative) {
  const auto model = make_model("torrance-sparrow", {{"fresnel", "exact-conductor"}});
  for (double ior : {0.02, 0.5, 1.0, 1.5, 3.0, 10.0}) {
    for (double k : {0.0, 1e-9, 0.5, 6.5}) {
      for (double roughness : {0.002, 0.2, 2.0}) {
        const double p[] = {1.0, roughness, ior, k};
        for (int ti = 0; ti <= 90; ti += 5) {
          for (int dphi = 0; dphi <= 180; dphi += 30) {
            const Geometry g = geometry_from_degrees(ti, 0.0, 90.0, dphi);
            const double f = model->evaluate(p, g);
            EXPECT_GE(f, 0.0) << "ior " << ior << " k " << k << " theta_i " << ti << " dphi " << dphi;
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace roadbrdf
