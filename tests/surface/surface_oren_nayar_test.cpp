// A random rough Lambertian surface against the Oren-Nayar model (Oren & Nayar, SIGGRAPH 1994).
//
// Reference: the paper's closed form (model "oren-nayar", full = direct eq. 30 + two-bounce
// interreflection eq. 37). Oren and Nayar derive it for isotropic V-cavity surfaces with Gaussian
// facet slopes and fit its coefficients to their numerical evaluation of that geometry; a random
// Gaussian-slope height field is a different microgeometry with the same slope statistics, so
// agreement is expected at the level of a few percent away from grazing, not exactly. The test
// uses sigma = the rms slope angle along a direction (make_gaussian_slope_surface), and checks:
//  - full rendering (all bounces) vs full model: within 12 % for theta_i, theta_r <= 60 deg;
//  - single-bounce rendering (max_bounces = 1) vs the direct term alone (the part linear in the
//    albedo, obtained as 4 f(rho/2) - f(rho)): within 12 % for the same geometries;
//  - the interreflection part (all bounces - single bounce) is at least the model's two-bounce term
//    (the rendering adds the higher orders) and at most 1.5 times it.
// Measured during development (20000 paths): largest deviation 10.2 % (single bounce, 45/45 deg,
// dphi = 180: the forward side, where the V-cavity and height-field shadowing differ most).
// At grazing forward geometries (75, 60, dphi 180) the difference reaches 17 % (not tested).
#include <gtest/gtest.h>

#include <cmath>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/models/registry.h"
#include "roadbrdf/surface/generate.h"
#include "roadbrdf/surface/render.h"

namespace rs = roadbrdf::surface;
using roadbrdf::Geometry;
using roadbrdf::geometry_from_degrees;

TEST(OrenNayar, GaussianSlopeLambertianSurfaceMatchesTheModel) {
  const double rho = 0.9, sigma = 0.3;
  rs::MaterialSpec m;
  m.name = "lambert";
  m.model = "lambert";
  m.parameters = {{"albedo", rho}};
  const rs::HeightField f = rs::make_gaussian_slope_surface(m, sigma, 128, 0.1, 1, 256);
  const rs::Renderer r(f, rs::load_materials(f, {550.0}), 1);
  const auto on = roadbrdf::make_model("oren-nayar");
  rs::RenderSettings st;
  st.samples = 20000;
  st.acceptance_half_angle_deg = 0.0;
  const double angles[][4] = {{0, 0, 0, 0},     {30, 0, 30, 0},   {60, 0, 60, 0}, {60, 0, 30, 0},   {60, 0, 30, 90},
                              {60, 0, 30, 180}, {30, 0, 60, 180}, {0, 0, 60, 0},  {45, 0, 45, 180}, {20, 0, 50, 120}};
  std::uint64_t stream = 0;
  for (const auto& a : angles) {
    const Geometry g = geometry_from_degrees(a[0], a[1], a[2], a[3]);
    const double p_full[2] = {rho, sigma}, p_half[2] = {0.5 * rho, sigma};
    const double full = on->evaluate(p_full, g);
    const double direct = 4.0 * on->evaluate(p_half, g) - full;  // f = a rho + b rho^2 -> a rho
    const double two_bounce = full - direct;
    st.max_bounces = 0;
    const rs::Estimate all = r.brdf(g, st, stream++);
    st.max_bounces = 1;
    const rs::Estimate single = r.brdf(g, st, stream++);
    EXPECT_NEAR(all.mean[0] / full, 1.0, 0.12) << a[0] << " " << a[2] << " " << a[3];
    EXPECT_NEAR(single.mean[0] / direct, 1.0, 0.12) << a[0] << " " << a[2] << " " << a[3];
    const double inter = all.mean[0] - single.mean[0];
    const double inter_sigma = std::hypot(all.standard_error[0], single.standard_error[0]);
    EXPECT_GT(inter + 3.0 * inter_sigma, two_bounce) << a[0] << " " << a[2] << " " << a[3];
    EXPECT_LT(inter - 3.0 * inter_sigma, 1.5 * two_bounce) << a[0] << " " << a[2] << " " << a[3];
  }
}
