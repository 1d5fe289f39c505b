// Albedo of a virtual sample (surface/virtual_albedo.h) against the deterministic hemisphere
// quadrature of albedo/hemisphere.h (an independent code path: adaptive Gauss-Kronrod x Sidi
// trapezoid over the model, no Monte Carlo) and the white furnace.
#include <gtest/gtest.h>
#include "support/materials.h"

#include <cmath>
#include <utility>
#include <vector>

#include "roadbrdf/albedo/hemisphere.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/progress.h"
#include "roadbrdf/models/registry.h"
#include "roadbrdf/surface/generate.h"
#include "roadbrdf/surface/render.h"
#include "roadbrdf/surface/virtual_albedo.h"

namespace rs = roadbrdf::surface;

namespace {

using roadbrdf::test::model_material;

rs::RenderSettings settings(long samples) {
  rs::RenderSettings s;
  s.samples = samples;
  s.acceptance_half_angle_deg = 0.0;
  s.threads = 2;
  return s;
}

}  // namespace

// A flat Oren-Nayar sample: black-sky at 0/30/60/75 deg and white-sky agree with the quadrature
// within 4 standard errors (plus 2e-4 for the 8-node Gauss-Legendre rule of the white-sky value).
TEST(VirtualAlbedo, FlatSampleMatchesTheHemisphereQuadrature) {
  const rs::HeightField f = rs::make_flat(model_material("oren-nayar", {{"albedo", 0.6}, {"sigma", 0.4}}), 8, 0.1);
  const std::vector<double> zeniths = {0.0, 30.0, 60.0, 75.0};
  const rs::VirtualAlbedo v = rs::render_albedo(f, zeniths, {550.0}, settings(40000));
  const auto model = roadbrdf::make_model("oren-nayar");
  const std::vector<double> p = {0.6, 0.4};
  for (std::size_t k = 0; k < zeniths.size(); ++k) {
    const auto ref = roadbrdf::albedo::black_sky(*model, p.data(), 1, roadbrdf::deg_to_rad(zeniths[k]));
    EXPECT_LT(v.black_sky_error[k][0], 2e-3);
    EXPECT_NEAR(v.black_sky[k][0], ref.value[0], 4.0 * v.black_sky_error[k][0] + 1e-6) << zeniths[k];
  }
  const auto white = roadbrdf::albedo::white_sky(*model, p.data(), 1);
  ASSERT_EQ(v.white_sky.size(), 1u);
  EXPECT_GT(v.white_sky_error[0], 0.0);
  EXPECT_NEAR(v.white_sky[0], white.value[0], 4.0 * v.white_sky_error[0] + 2e-4);
}

// White furnace: a rough sample of a non-absorbing Lambertian material reflects everything, for a
// collimated sun and for isotropic illumination (white-sky 1 within noise).
TEST(VirtualAlbedo, WhiteFurnaceGivesOne) {
  const rs::HeightField f =
      rs::make_gaussian_slope_surface(model_material("lambert", {{"albedo", 1.0}}), 0.5, 64, 0.1, 4, 256);
  const rs::VirtualAlbedo v = rs::render_albedo(f, {45.0}, {550.0}, settings(20000), 6);
  EXPECT_NEAR(v.black_sky[0][0], 1.0, 4.0 * v.black_sky_error[0][0] + 1e-9);
  EXPECT_NEAR(v.white_sky[0], 1.0, 4.0 * v.white_sky_error[0] + 1e-9);
}

TEST(VirtualAlbedo, RejectsBadAngles) {
  const rs::HeightField f = rs::make_flat(model_material("lambert", {{"albedo", 0.5}}), 8, 0.1);
  EXPECT_THROW(rs::render_albedo(f, {90.0}, {550.0}, settings(16)), roadbrdf::InputError);
  EXPECT_THROW(rs::render_albedo(f, {-1.0}, {550.0}, settings(16)), roadbrdf::InputError);
  EXPECT_THROW(rs::render_albedo(f, {30.0}, {}, settings(16)), roadbrdf::InputError);
}

// Progress (core/progress.h): the renderer reports blocks of paths (ceil(samples / paths_per_block)
// per geometry, so the total is known before any path is traced), render_albedo reports its
// estimates (sun zeniths + white-sky nodes); both counts never decrease and end at the total.
namespace {

struct Recorder {
  std::vector<std::pair<std::size_t, std::size_t>> calls;
  roadbrdf::ProgressCallback callback() {
    return [this](std::size_t done, std::size_t total) { calls.emplace_back(done, total); };
  }
  bool monotone() const {
    for (std::size_t k = 1; k < calls.size(); ++k) {
      if (calls[k].first < calls[k - 1].first) return false;
    }
    return true;
  }
};

}  // namespace

TEST(Progress, RendererReportsBlocksAndAlbedoReportsEstimates) {
  const rs::HeightField f = rs::make_flat(model_material("lambert", {{"albedo", 0.5}}), 8, 0.1);
  const rs::Renderer r(f, rs::load_materials(f, {550.0}), 1);
  Recorder blocks;
  rs::RenderSettings s = settings(1000);
  s.paths_per_block = 300;  // 4 blocks per geometry (300, 300, 300, 100)
  s.progress = blocks.callback();
  const std::vector<roadbrdf::Geometry> g = {roadbrdf::geometry_from_degrees(0, 0, 30, 0),
                                             roadbrdf::geometry_from_degrees(30, 0, 45, 180),
                                             roadbrdf::geometry_from_degrees(60, 0, 10, 90)};
  r.brdf(g, s);
  ASSERT_FALSE(blocks.calls.empty());
  EXPECT_TRUE(blocks.monotone());
  EXPECT_EQ(blocks.calls.back(), std::make_pair(std::size_t{12}, std::size_t{12}));
  for (const auto& c : blocks.calls) EXPECT_EQ(c.second, 12u);

  Recorder estimates;
  rs::RenderSettings a = settings(64);
  a.progress = estimates.callback();
  rs::render_albedo(f, {0.0, 30.0, 60.0}, {550.0}, a, 4);
  const std::vector<std::pair<std::size_t, std::size_t>> expected = {{1, 7}, {2, 7}, {3, 7}, {4, 7},
                                                                     {5, 7}, {6, 7}, {7, 7}, {7, 7}};
  EXPECT_EQ(estimates.calls, expected);  // one per estimate (one thread calls), then finish
}
