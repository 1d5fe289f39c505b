#include "roadbrdf/core/geometry.h"

#include <gtest/gtest.h>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"

namespace roadbrdf {
namespace {

TEST(Geometry, DirectionsPointAwayFromSurface) {
  const Geometry g = geometry_from_degrees(30.0, 0.0, 60.0, 180.0);
  EXPECT_NEAR(g.wi.z, std::cos(30.0 * kDegree), 1e-15);
  EXPECT_NEAR(g.wr.z, 0.5, 1e-15);
  EXPECT_NEAR(g.wi.x, 0.5, 1e-15);
  EXPECT_NEAR(g.wr.x, -std::sin(60.0 * kDegree), 1e-15);
  EXPECT_NEAR(g.cos_delta_phi, -1.0, 1e-15);  // forward (specular) side
}

TEST(Geometry, MirrorDirectionIsSpecular) {
  const Geometry g = geometry_from_degrees(40.0, 10.0, 40.0, 190.0);
  const Vec3 m = mirror_direction(g.wi);
  EXPECT_NEAR(dot(m, g.wr), 1.0, 1e-14);
  const Vec3 h = g.half_vector();
  EXPECT_NEAR(h.z, 1.0, 1e-14);
}

TEST(Geometry, GrazingIsExactlyGrazing) {
  const Geometry g = geometry_from_degrees(90.0, 0.0, 0.0, 0.0);
  EXPECT_EQ(g.wi.z, 0.0);
  EXPECT_EQ(g.cos_delta_phi, 0.0);  // azimuth undefined at the normal
}

TEST(Geometry, RejectsZenithOutsideRange) {
  EXPECT_THROW(geometry_from_degrees(91.0, 0, 0, 0), InputError);
  EXPECT_THROW(geometry_from_degrees(0, 0, -1.0, 0), InputError);
  EXPECT_THROW(geometry_from_degrees(std::nan(""), 0, 0, 0), InputError);
}

TEST(Geometry, RoadAnglesFollowTheReportConvention) {
  // gamma = theta_i; alpha = 90 - theta_r; beta = 180 - (phi_r - phi_i); delta = phi_r - 180.
  // CIE observation angle alpha = 1 deg is theta_r = 89 deg; beta = 0 is the forward side.
  const Geometry g = geometry_from_road_angles({60.0, 1.0, 0.0, 0.0});
  EXPECT_NEAR(g.theta_i, 60.0 * kDegree, 1e-15);
  EXPECT_NEAR(g.theta_r, 89.0 * kDegree, 1e-15);
  EXPECT_NEAR(g.cos_delta_phi, -1.0, 1e-15);
  const Geometry retro = geometry_from_road_angles({60.0, 1.0, 180.0, 0.0});
  EXPECT_NEAR(retro.cos_delta_phi, 1.0, 1e-15);
  const RoadAngles back = road_angles_from_geometry(geometry_from_road_angles({35.0, 12.0, 45.0, 20.0}));
  EXPECT_NEAR(back.gamma, 35.0, 1e-12);
  EXPECT_NEAR(back.alpha, 12.0, 1e-12);
  EXPECT_NEAR(back.beta, 45.0, 1e-12);
  EXPECT_NEAR(back.delta, 20.0, 1e-12);
}

}  // namespace
}  // namespace roadbrdf
