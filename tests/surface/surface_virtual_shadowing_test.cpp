// The fact the virtual mixing study rests on (docs/virtual-study.md): the light a recessed material
// (the mastic between protruding grains) contributes to a virtual measurement is set by the part of
// its area that is both lit and seen, not by its projected area fraction. Checked on a surface with
// a closed-form answer: periodic ridges (black) and trenches whose flat bottom is a white Lambertian
// material, lit and seen in the plane across the trenches, single scattering.
//
// Geometry (nodes x = i h, heights z_i = H on the ridge nodes i = 0..a, 0 on i = a+1..P-1, constant
// along y): the trench bottom is the cells a+1..P-2, x in [(a+1) h, (P-1) h]; the walls are the cells a
// and P-1 (one cell wide, corners at x = a h and x = P h at height H); the ridge tops and walls are
// black (their cells carry material 0). A bottom point x is lit by a source at azimuth 0 (towards +x)
// when the ray to it clears the corner at x = P h: x <= P h - H tan(theta_i); it is seen by a detector
// on the source side (azimuth 0) when x <= P h - H tan(theta_r), and from the opposite side (azimuth
// 180 deg) when x >= a h + H tan(theta_r) (a line rising from a point of the bottom that clears the
// corner stays above the straight wall, so the corner alone decides). The bottom is horizontal, so a
// parallel beam of sight lines maps horizontal widths one to one onto the mean plane, and the
// single-scattering BRDF of the sample is exactly
//     f = (rho / pi) * (lit and seen width of the bottom) / (P h).
// Projected fraction of the bottom: (P - a - 2) / P. Reference: this elementary geometry, not the code.
#include <gtest/gtest.h>
#include "support/materials.h"

#include <algorithm>
#include <cmath>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/surface/height_field.h"
#include "roadbrdf/surface/render.h"

namespace rs = roadbrdf::surface;
using roadbrdf::kPi;

namespace {

constexpr int kP = 20;      // nodes (= cells) per period along x
constexpr int kA = 5;       // ridge nodes 0..kA
constexpr double kH = 0.5;  // ridge height [mm]
constexpr double kCell = 0.1;
constexpr double kRho = 0.8;

using roadbrdf::test::lambert;

rs::HeightField trenches() {
  rs::HeightField f;
  f.name = "ridges and trenches";
  f.cell_size_mm = kCell;
  f.nx = kP;
  f.ny = 8;
  f.heights.assign(static_cast<std::size_t>(f.nx) * f.ny, 0.0);
  f.material.assign(f.heights.size(), 0);
  for (int j = 0; j < f.ny; ++j) {
    for (int i = 0; i < f.nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * f.nx + i;
      if (i <= kA) f.heights[k] = kH;
      if (i >= kA + 1 && i <= kP - 2) f.material[k] = 1;  // flat trench bottom
    }
  }
  f.materials = {lambert(0.0), lambert(kRho)};
  return f;
}

// Lit-and-seen width [mm] of the trench bottom (closed form above).
double lit_and_seen_width(double theta_i_deg, double theta_r_deg, bool forward) {
  const double h = kCell, ti = std::tan(roadbrdf::deg_to_rad(theta_i_deg)),
               tr = std::tan(roadbrdf::deg_to_rad(theta_r_deg));
  double lo = (kA + 1) * h, hi = std::min((kP - 1) * h, kP * h - kH * ti);
  if (forward) {
    lo = std::max(lo, kA * h + kH * tr);
  } else {
    hi = std::min(hi, kP * h - kH * tr);
  }
  return std::max(0.0, hi - lo);
}

}  // namespace

TEST(SurfaceVirtualShadowing, RecessedMaterialContributesItsLitAndSeenAreaNotItsProjectedArea) {
  const rs::HeightField field = trenches();
  const std::vector<double> wavelengths{550.0};
  rs::Renderer renderer(field, rs::load_materials(field, wavelengths), 1);
  rs::RenderSettings s;
  s.samples = 40000;
  s.acceptance_half_angle_deg = 0.0;  // ideal detector: the closed form holds exactly
  s.max_bounces = 1;                  // single scattering (the walls and tops are black anyway)
  s.threads = 2;
  const double period = kP * kCell;
  const double projected = (kP - kA - 2) / static_cast<double>(kP);
  struct Case {
    double theta_i, theta_r;
    bool forward;
  };
  // Normal, moderate and grazing, backscatter (viewer on the source side) and forward.
  const Case cases[] = {{0, 0, false},  {20, 20, false}, {40, 10, false}, {60, 60, false},
                        {20, 20, true}, {40, 40, true},  {60, 30, true},  {70, 70, true}};
  int strongly_below_projected = 0;
  for (std::size_t k = 0; k < std::size(cases); ++k) {
    const Case& c = cases[k];
    const roadbrdf::Geometry g = roadbrdf::geometry_from_degrees(c.theta_i, 0.0, c.theta_r, c.forward ? 180.0 : 0.0);
    const rs::Estimate e = renderer.brdf(g, s, k);
    const double expected = kRho / kPi * lit_and_seen_width(c.theta_i, c.theta_r, c.forward) / period;
    // Binomial standard error of a mean of values rho/pi or 0 (p = expected fraction), floor for p = 0.
    const double p = expected / (kRho / kPi);
    const double sigma = (kRho / kPi) * std::sqrt(std::max(p * (1.0 - p), 1.0 / s.samples) / s.samples);
    EXPECT_NEAR(e.mean[0], expected, 4.0 * sigma)
        << "theta_i " << c.theta_i << ", theta_r " << c.theta_r << (c.forward ? " forward" : " backscatter");
    if (e.mean[0] < 0.5 * projected * kRho / kPi) ++strongly_below_projected;
  }
  // The point of the test: at oblique geometries the recessed material's weight falls far below its
  // projected area fraction (60/60 backscatter, 60/30 and 70/70 forward; at normal incidence and
  // viewing the two agree, the first case).
  EXPECT_GE(strongly_below_projected, 3);
}
