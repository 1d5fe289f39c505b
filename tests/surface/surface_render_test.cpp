// Virtual gonioreflectometer: flat samples, white furnace, reciprocity, standard error.
#include <gtest/gtest.h>
#include "support/materials.h"

#include <cmath>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/models/registry.h"
#include "roadbrdf/surface/generate.h"
#include "roadbrdf/surface/height_field.h"
#include "roadbrdf/surface/render.h"

namespace rs = roadbrdf::surface;
using roadbrdf::Geometry;
using roadbrdf::geometry_from_degrees;
using roadbrdf::kPi;

namespace {

using roadbrdf::test::model_material;

rs::RenderSettings settings(long samples, double acceptance, int threads = 2, std::uint64_t seed = 1) {
  rs::RenderSettings s;
  s.samples = samples;
  s.acceptance_half_angle_deg = acceptance;
  s.threads = threads;
  s.seed = seed;
  return s;
}

// Independent reference: the cone average (1/Omega) int_cone f dw of a model by Gauss-Legendre
// quadrature in cos(alpha) (alpha = angle from the cone axis) and the midpoint rule in azimuth.
double cone_average(const roadbrdf::Model& model, const std::vector<double>& p, const Geometry& g,
                    double half_angle_deg) {
  static const double x[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                              0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
  static const double w[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066578778373, 0.3626837833783620,
                              0.3626837833783620, 0.3137066578778373, 0.2223810344533745, 0.1012285362903763};
  const double cd = std::cos(roadbrdf::deg_to_rad(half_angle_deg));
  // Axis frame.
  const roadbrdf::Vec3 a = g.wr;
  roadbrdf::Vec3 t = std::fabs(a.z) < 0.9 ? roadbrdf::Vec3{0, 0, 1} : roadbrdf::Vec3{1, 0, 0};
  t = roadbrdf::normalize(t - roadbrdf::dot(t, a) * a);
  const roadbrdf::Vec3 b{a.y * t.z - a.z * t.y, a.z * t.x - a.x * t.z, a.x * t.y - a.y * t.x};
  double sum = 0.0;
  const int n_phi = 64;
  for (int k = 0; k < 8; ++k) {
    const double ca = 0.5 * (1.0 + cd) + 0.5 * (1.0 - cd) * x[k];
    const double sa = std::sqrt(1.0 - ca * ca);
    for (int m = 0; m < n_phi; ++m) {
      const double ph = 2 * kPi * (m + 0.5) / n_phi;
      const roadbrdf::Vec3 d = (sa * std::cos(ph)) * t + (sa * std::sin(ph)) * b + ca * a;
      const double th = std::acos(std::min(1.0, d.z)), phr = std::atan2(d.y, d.x);
      const Geometry gg = roadbrdf::geometry_from_radians(g.theta_i, g.phi_i, th, phr);
      sum += 0.5 * w[k] * model.evaluate(p.data(), gg) / n_phi;
    }
  }
  return sum;
}

}  // namespace

// A flat sample seen along an ideal direction (no cone): every path gives exactly the material's
// BRDF (the single bounce is deterministic), so the estimate is exact and its standard error 0.
TEST(FlatSample, IdealDetectorReproducesTheMaterialExactly) {
  const auto mat = model_material("oren-nayar", {{"albedo", 0.6}, {"sigma", 0.4}});
  const rs::HeightField f = rs::make_flat(mat, 8, 0.1);
  const rs::Renderer r(f, rs::load_materials(f, {550.0}), 1);
  const auto model = roadbrdf::make_model("oren-nayar");
  const std::vector<double> p = {0.6, 0.4};
  const double angles[][4] = {{0, 0, 30, 0},   {30, 0, 30, 180}, {60, 20, 45, 20},  {60, 10, 70, 190},
                              {45, 0, 45, 90}, {75, 0, 10, 250}, {20, 300, 80, 30}, {60, 0, 60, 0}};
  for (const auto& a : angles) {
    const Geometry g = geometry_from_degrees(a[0], a[1], a[2], a[3]);
    const rs::Estimate e = r.brdf(g, settings(16, 0.0));
    EXPECT_NEAR(e.mean[0], model->evaluate(p.data(), g), 1e-9 * model->evaluate(p.data(), g))
        << a[0] << " " << a[1] << " " << a[2] << " " << a[3];
    EXPECT_NEAR(e.standard_error[0], 0.0, 1e-9);
  }
}

// With a 5 deg cone the flat sample gives the cone average of a glossy material's BRDF (here the
// default oren-nayar+torrance-sparrow composite), within the reported standard error.
TEST(FlatSample, ConeAverageOfAGlossyMaterialWithinStandardError) {
  const auto model = roadbrdf::make_model("oren-nayar+torrance-sparrow");
  const std::vector<double> p = model->description().default_parameters();
  rs::MaterialSpec mat;
  mat.name = "glossy";
  mat.model = "oren-nayar+torrance-sparrow";
  const rs::HeightField f = rs::make_flat(mat, 8, 0.1);
  const std::vector<double> wl = {450.0, 650.0};
  const rs::Renderer r(f, rs::load_materials(f, wl), wl.size());
  const double angles[][4] = {{30, 0, 30, 180}, {60, 0, 55, 180}, {45, 0, 30, 60}, {10, 0, 40, 0}};
  for (const auto& a : angles) {
    const Geometry g = geometry_from_degrees(a[0], a[1], a[2], a[3]);
    const rs::Estimate e = r.brdf(g, settings(20000, 5.0));
    const double ref = cone_average(*model, p, g, 5.0);
    for (std::size_t w = 0; w < wl.size(); ++w) {
      EXPECT_GT(e.standard_error[w], 0.0);
      EXPECT_LT(e.standard_error[w], 0.02 * ref);
      EXPECT_NEAR(e.mean[w], ref, 4.0 * e.standard_error[w]) << a[0] << " " << a[2] << " " << a[3];
    }
  }
}

// A flat sample of a material with an ideal specular part (simonot: Lambertian under a flat
// interface): the 5 deg detector sees the smooth part's cone average plus, when the mirror direction
// is inside its cone, the spike R(theta_i) / (Omega cos theta_s) (the cone average of
// R delta(w - w_s) / cos theta). R from the Fresnel equations written out here.
TEST(FlatSample, SpecularSpikeOfADeltaPartThroughTheCone) {
  const auto model = roadbrdf::make_model("simonot");
  std::vector<double> p = model->description().default_parameters();
  const double ior = p[*model->description().parameter_index("ior")];
  rs::MaterialSpec mat;
  mat.name = "interface";
  mat.model = "simonot";
  const rs::HeightField f = rs::make_flat(mat, 8, 0.1);
  const rs::Renderer r(f, rs::load_materials(f, {550.0}), 1);
  const double half = 5.0, omega = 2 * kPi * (1 - std::cos(roadbrdf::deg_to_rad(half)));
  const double ci = std::cos(roadbrdf::deg_to_rad(30.0)), si = std::sin(roadbrdf::deg_to_rad(30.0));
  const double ct = std::sqrt(1 - si * si / (ior * ior));
  const double rs_ = std::pow((ci - ior * ct) / (ci + ior * ct), 2),
               rp = std::pow((ior * ci - ct) / (ior * ci + ct), 2);
  const double R = 0.5 * (rs_ + rp);
  // theta_r = 30 (mirror: spike seen), 33 (mirror 3 deg off the axis: seen), 40 (outside the cone).
  const double cases[][2] = {{30.0, 1.0}, {33.0, 1.0}, {40.0, 0.0}};
  for (const auto& c : cases) {
    const Geometry g = geometry_from_degrees(30, 0, c[0], 180);
    const rs::Estimate e = r.brdf(g, settings(20000, half));
    const double ref = cone_average(*model, p, g, half) + c[1] * R / (omega * ci);
    EXPECT_NEAR(e.mean[0], ref, 4.0 * e.standard_error[0] + 1e-12 * ref) << c[0];
    if (c[1] > 0) {
      EXPECT_GT(e.mean[0], 10.0 * cone_average(*model, p, g, half));
    }
  }
}

// White furnace: a non-absorbing Lambertian material (albedo 1) reflects all the light whatever
// the roughness, so the directional albedo is 1 at every incidence; an albedo-0.7 flat sample has 0.7.
TEST(WhiteFurnace, RoughWhiteLambertianHasDirectionalAlbedoOne) {
  const auto white = model_material("lambert", {{"albedo", 1.0}});
  const rs::HeightField f = rs::make_gaussian_slope_surface(white, 0.6, 64, 0.1, 4, 256);
  const rs::Renderer r(f, rs::load_materials(f, {550.0}), 1);
  for (double theta : {0.0, 30.0, 60.0, 80.0}) {
    const rs::Estimate e = r.directional_albedo(roadbrdf::deg_to_rad(theta), 0.3, settings(100000, 0.0));
    EXPECT_LT(e.standard_error[0], 0.01);
    EXPECT_NEAR(e.mean[0], 1.0, 4.0 * e.standard_error[0] + 1e-9) << theta;
  }
  const rs::HeightField flat = rs::make_flat(model_material("lambert", {{"albedo", 0.7}}), 8, 0.1);
  const rs::Renderer rf(flat, rs::load_materials(flat, {550.0}), 1);
  const rs::Estimate e = rf.directional_albedo(roadbrdf::deg_to_rad(40.0), 0.0, settings(20000, 0.0));
  EXPECT_NEAR(e.mean[0], 0.7, 1e-12);  // every path: pi * 0.7/pi, no variance
}

// A rough sample of a non-absorbing material with an ideal specular part (Simonot's interfaced
// Lambertian with background reflectance 1): all the light comes back, including the paths whose
// first reflection from the source is the mirror part and that hit the surface again (without the
// source-side delta paths (path_integrator.cpp) the albedo was 0.98 / 0.966 / 0.973 here, 10 sigma low).
TEST(WhiteFurnace, RoughSampleOfANonAbsorbingMaterialWithAMirrorPart) {
  const auto white = model_material("simonot", {{"albedo", 1.0}, {"ior", 1.5}});
  const rs::HeightField f = rs::make_gaussian_slope_surface(white, 0.5, 64, 0.1, 1, 256);
  const rs::Renderer r(f, rs::load_materials(f, {550.0}), 1);
  for (double theta : {0.0, 40.0, 70.0}) {
    const rs::Estimate e = r.directional_albedo(roadbrdf::deg_to_rad(theta), 0.0, settings(60000, 0.0));
    EXPECT_LT(e.standard_error[0], 0.005);
    EXPECT_NEAR(e.mean[0], 1.0, 4.0 * e.standard_error[0]) << theta;
  }
}

// The same on a generated road sample (steep grain flanks, many interreflections).
TEST(WhiteFurnace, GeneratedGrainSampleOfWhiteMaterials) {
  rs::SampleRecipe recipe;
  recipe.name = "white grains";
  recipe.matrix = model_material("lambert", {{"albedo", 1.0}});
  rs::GrainClass c;
  c.material = model_material("oren-nayar", {{"albedo", 1.0}, {"sigma", 0.0}});  // = Lambert, albedo 1
  c.d_min_mm = 2;
  c.d_max_mm = 4;
  c.volume_fraction = 0.25;
  recipe.classes = {c};
  rs::GeneratorSettings gs;
  gs.size_mm = 10.0;
  gs.cell_size_mm = 0.1;
  gs.matrix_level = 0.3;
  const rs::GeneratedSample sample = rs::generate_sample(recipe, gs);
  const rs::Renderer r(sample.field, rs::load_materials(sample.field, {550.0}), 1);
  for (double theta : {0.0, 45.0, 75.0}) {
    const rs::Estimate e = r.directional_albedo(roadbrdf::deg_to_rad(theta), 1.0, settings(100000, 0.0));
    EXPECT_LT(e.standard_error[0], 0.01);
    EXPECT_NEAR(e.mean[0], 1.0, 4.0 * e.standard_error[0] + 1e-9) << theta;
  }
}

// Reciprocity: with an ideal detector the estimate is the footprint-averaged BRDF of the rough
// sample, which must be symmetric in (w_i, w_r) (Helmholtz), here with a glossy + diffuse material
// and interreflections.
TEST(Reciprocity, SwappedGeometriesAgreeWithinNoise) {
  rs::MaterialSpec mat;
  mat.name = "glossy";
  mat.model = "oren-nayar+torrance-sparrow";
  const rs::HeightField f = rs::make_gaussian_slope_surface(mat, 0.5, 64, 0.1, 9, 256);
  const rs::Renderer r(f, rs::load_materials(f, {550.0}), 1);
  const double angles[][4] = {{20, 0, 60, 180}, {70, 0, 30, 90}, {50, 30, 10, 200}, {80, 0, 40, 0}};
  for (const auto& a : angles) {
    const Geometry g = geometry_from_degrees(a[0], a[1], a[2], a[3]);
    const rs::Estimate e1 = r.brdf(g, settings(40000, 0.0, 2, 1));
    const rs::Estimate e2 = r.brdf(g.swapped(), settings(40000, 0.0, 2, 2));
    const double s = std::hypot(e1.standard_error[0], e2.standard_error[0]);
    EXPECT_LT(s, 0.05 * e1.mean[0]);
    EXPECT_NEAR(e1.mean[0], e2.mean[0], 4.0 * s) << a[0] << " " << a[2] << " " << a[3];
  }
}

// The standard error falls as 1/sqrt(N), the reported error matches the scatter of independent
// runs, and the result does not depend on the number of threads.
TEST(StandardError, ShrinksAsOneOverSqrtNAndIsCalibrated) {
  const auto mat = model_material("lambert", {{"albedo", 0.8}});
  const rs::HeightField f = rs::make_gaussian_slope_surface(mat, 0.5, 64, 0.1, 5, 256);
  const rs::Renderer r(f, rs::load_materials(f, {550.0}), 1);
  const Geometry g = geometry_from_degrees(40, 0, 30, 180);
  const rs::Estimate small = r.brdf(g, settings(2000, 1.0));
  const rs::Estimate large = r.brdf(g, settings(32000, 1.0));
  EXPECT_NEAR(small.standard_error[0] / large.standard_error[0], 4.0, 0.4);

  // 40 independent runs of 500 paths: the sample standard deviation of their means estimates the
  // true standard error with a relative uncertainty of about 1/sqrt(2*39) = 11 %.
  const int runs = 40;
  double sum = 0.0, sum2 = 0.0, reported = 0.0;
  for (int k = 0; k < runs; ++k) {
    const rs::Estimate e = r.brdf(g, settings(500, 1.0, 2, 100 + k));
    sum += e.mean[0];
    sum2 += e.mean[0] * e.mean[0];
    reported += e.standard_error[0] / runs;
  }
  const double mean = sum / runs;
  const double spread = std::sqrt((sum2 - runs * mean * mean) / (runs - 1));
  EXPECT_NEAR(spread / reported, 1.0, 0.35);

  const rs::Estimate one = r.brdf(g, settings(3000, 1.0, 1));
  const rs::Estimate three = r.brdf(g, settings(3000, 1.0, 3));
  EXPECT_EQ(one.mean, three.mean);
  EXPECT_EQ(one.standard_error, three.standard_error);
}

// BRDF importance sampling (brdf_sampler.h, one-sample MIS with cosine sampling) and cosine
// sampling are two unbiased estimators of the same quantity: on a rough surface of a glossy material
// (small Torrance-Sparrow roughness, where interreflection paths go through the glossy lobe) they
// agree within their combined standard error, with and without the multiple-bounce part.
TEST(BrdfSampling, AgreesWithCosineSamplingOnARoughGlossySurface) {
  rs::MaterialSpec mat;
  mat.name = "glossy";
  mat.model = "oren-nayar+torrance-sparrow";
  mat.parameters = {{"oren-nayar.albedo", 0.5}, {"torrance-sparrow.roughness", 0.08}};
  const rs::HeightField f = rs::make_gaussian_slope_surface(mat, 0.5, 64, 0.1, 3, 256);
  const rs::Renderer r(f, rs::load_materials(f, {550.0}), 1);
  const double angles[][4] = {{60, 0, 60, 180}, {30, 0, 45, 90}, {70, 0, 20, 0}};
  for (const auto& a : angles) {
    const Geometry g = geometry_from_degrees(a[0], a[1], a[2], a[3]);
    rs::RenderSettings sc = settings(40000, 1.0, 2, 1), sb = settings(40000, 1.0, 2, 2);
    sc.sampling = rs::Sampling::cosine;
    sb.sampling = rs::Sampling::brdf;
    const rs::Estimate ec = r.brdf(g, sc), eb = r.brdf(g, sb);
    const double s = std::hypot(ec.standard_error[0], eb.standard_error[0]);
    EXPECT_LT(s, 0.05 * ec.mean[0]);
    EXPECT_NEAR(ec.mean[0], eb.mean[0], 4.0 * s) << a[0] << " " << a[2] << " " << a[3];
  }
}

// White furnace with BRDF sampling: the tabulated sampler of a Lambertian material is not exactly
// the cosine density (piecewise constant), so the MIS weights are exercised; the albedo stays 1.
TEST(BrdfSampling, WhiteFurnace) {
  const auto white = model_material("lambert", {{"albedo", 1.0}});
  const rs::HeightField f = rs::make_gaussian_slope_surface(white, 0.6, 64, 0.1, 4, 256);
  const rs::Renderer r(f, rs::load_materials(f, {550.0}), 1);
  for (double theta : {0.0, 60.0}) {
    rs::RenderSettings s = settings(100000, 0.0);
    s.sampling = rs::Sampling::brdf;
    s.brdf_sampling_fraction = 0.9;
    const rs::Estimate e = r.directional_albedo(roadbrdf::deg_to_rad(theta), 0.3, s);
    EXPECT_LT(e.standard_error[0], 0.01);
    EXPECT_NEAR(e.mean[0], 1.0, 4.0 * e.standard_error[0] + 1e-9) << theta;
  }
}

// Adaptive sampling: every geometry reaches the target (or is flagged), uses at least min_blocks
// blocks, does not depend on the thread count, and agrees with a long fixed-count run.
TEST(AdaptiveSampling, ReachesTheTargetDeterministically) {
  const auto mat = model_material("lambert", {{"albedo", 0.8}});
  const rs::HeightField f = rs::make_gaussian_slope_surface(mat, 0.5, 64, 0.1, 5, 256);
  const rs::Renderer r(f, rs::load_materials(f, {450.0, 650.0}), 2);
  const std::vector<Geometry> gs = {geometry_from_degrees(40, 0, 30, 180), geometry_from_degrees(0, 0, 60, 0),
                                    geometry_from_degrees(75, 0, 70, 180)};
  rs::RenderSettings s = settings(0, 1.0, 1);
  s.target_relative_error = 0.01;
  const std::vector<rs::Estimate> one = r.brdf(gs, s);
  s.threads = 3;
  const std::vector<rs::Estimate> three = r.brdf(gs, s);
  for (std::size_t k = 0; k < gs.size(); ++k) {
    EXPECT_TRUE(one[k].converged);
    EXPECT_GE(one[k].paths, s.min_blocks * s.paths_per_block);
    EXPECT_LE(one[k].worst_relative_error(), 0.01);
    EXPECT_GT(one[k].worst_relative_error(), 0.003);  // not far past the target
    EXPECT_EQ(one[k].mean, three[k].mean);
    EXPECT_EQ(one[k].paths, three[k].paths);
    // Reference: an independent fixed run with 4x the paths (different seed).
    const rs::Estimate ref = r.brdf(gs[k], settings(4 * one[k].paths, 1.0, 2, 99), 1000 + k);
    for (std::size_t w = 0; w < 2; ++w) {
      EXPECT_NEAR(one[k].mean[w], ref.mean[w], 4.0 * std::hypot(one[k].standard_error[w], ref.standard_error[w]));
    }
  }
}

// A geometry that cannot reach the target within max_samples stops there and is flagged; a
// deterministic one (flat sample, ideal detector: error 0) stops after the minimum blocks.
TEST(AdaptiveSampling, StopsAtTheMaximumAndFlagsIt) {
  const auto mat = model_material("lambert", {{"albedo", 0.8}});
  const rs::HeightField f = rs::make_gaussian_slope_surface(mat, 0.5, 64, 0.1, 5, 256);
  const rs::Renderer r(f, rs::load_materials(f, {550.0}), 1);
  rs::RenderSettings s = settings(0, 1.0);
  s.target_relative_error = 1e-4;
  s.max_samples = 3000;  // not a whole number of blocks
  const rs::Estimate e = r.brdf(geometry_from_degrees(40, 0, 30, 180), s);
  EXPECT_FALSE(e.converged);
  EXPECT_EQ(e.paths, 3000);
  EXPECT_GT(e.worst_relative_error(), 1e-4);

  const rs::HeightField flat = rs::make_flat(mat, 8, 0.1);
  const rs::Renderer rf(flat, rs::load_materials(flat, {550.0}), 1);
  s.acceptance_half_angle_deg = 0.0;
  const rs::Estimate ef = rf.brdf(geometry_from_degrees(40, 0, 30, 180), s);
  EXPECT_TRUE(ef.converged);
  EXPECT_EQ(ef.paths, s.min_blocks * s.paths_per_block);
  EXPECT_NEAR(ef.mean[0], 0.8 / kPi, 1e-12);
}

// A round of blocks too large for chunk_bytes runs in chunks (here one block at a time): fixed and
// adaptive estimates are the same numbers, bit for bit, as when every block of a round runs at once.
TEST(Scheduling, ChunkedRoundsGiveTheSameEstimates) {
  const auto mat = model_material("lambert", {{"albedo", 0.8}});
  const rs::HeightField f = rs::make_gaussian_slope_surface(mat, 0.5, 64, 0.1, 5, 256);
  const rs::Renderer r(f, rs::load_materials(f, {450.0, 650.0}), 2);
  const std::vector<Geometry> gs = {geometry_from_degrees(40, 0, 30, 180), geometry_from_degrees(0, 0, 60, 0)};
  for (const double target : {0.0, 0.02}) {
    rs::RenderSettings s = settings(target > 0.0 ? 0 : 3000, 1.0, 2);
    s.target_relative_error = target;
    const std::vector<rs::Estimate> whole = r.brdf(gs, s);
    s.chunk_bytes = 1;
    const std::vector<rs::Estimate> chunked = r.brdf(gs, s);
    for (std::size_t k = 0; k < gs.size(); ++k) {
      EXPECT_EQ(whole[k].paths, chunked[k].paths) << target;
      EXPECT_EQ(whole[k].mean, chunked[k].mean) << target;
      EXPECT_EQ(whole[k].standard_error, chunked[k].standard_error) << target;
      EXPECT_EQ(whole[k].converged, chunked[k].converged) << target;
    }
  }
}
