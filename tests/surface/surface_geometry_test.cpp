// Virtual samples: height field, texture statistics, SURFACE files, exact ray traversal, generator.
#include <gtest/gtest.h>
#include "support/materials.h"
#include "support/scratch.h"

#include <cmath>
#include <filesystem>
#include <fstream>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/random.h"
#include "roadbrdf/surface/generate.h"
#include "roadbrdf/surface/height_field.h"
#include "roadbrdf/surface/render.h"

namespace rs = roadbrdf::surface;
using roadbrdf::kPi;
using roadbrdf::Vec3;

namespace {

rs::MaterialSpec lambert(double albedo, const std::string& name = "white") {
  return roadbrdf::test::lambert(albedo, name);
}

std::string temp_path(const std::string& name) { return roadbrdf::test::scratch_path("surface_test_" + name); }

}  // namespace

TEST(HeightField, MpdOfACosineProfileByHand) {
  // z = A cos(2 pi (k - (n-1)/2) / n) along x and the same along y: every row and column profile is
  // a cosine plus a constant, symmetric about its centre (no linear trend); its two half-period
  // maxima are both A cos(pi/n) (the samples nearest the centre) and its mean is 0, so
  // MPD = A cos(pi / n) (ISO 13473-1: mean of the two half-segment peaks minus the mean level).
  const int n = 40;
  const double A = 0.7;
  rs::HeightField f = rs::make_flat(lambert(0.5), n, 0.25);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      f.heights[j * n + i] =
          A * std::cos(2 * kPi * (i - (n - 1) / 2.0) / n) + A * std::cos(2 * kPi * (j - (n - 1) / 2.0) / n);
    }
  }
  const rs::TextureStatistics s = rs::texture_statistics(f);
  EXPECT_NEAR(s.mpd_mm, A * std::cos(kPi / n), 1e-12);
  EXPECT_NEAR(s.etd_mm, 0.2 + 0.8 * A * std::cos(kPi / n), 1e-12);
  // rms of a sum of two independent full-period cosines: sqrt(2 * A^2 / 2) = A.
  EXPECT_NEAR(s.rms_height_mm, A, 1e-12);
}

TEST(HeightField, AreaFractionsOfACheckerboard) {
  const int n = 8;
  rs::HeightField f = rs::make_flat(lambert(0.5, "a"), n, 0.1);
  f.materials.push_back(lambert(0.2, "b"));
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) f.material[j * n + i] = (i + j) % 2;
  }
  // A tilted plane z = 0.1 x would not be periodic; use a ridge along x: z = 0.05 |i - 4| has
  // slopes +-0.5 everywhere, so the true area is sqrt(1 + 0.25) of the projected one.
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) f.heights[j * n + i] = 0.05 * std::abs(i - 4);
  }
  const rs::TextureStatistics s = rs::texture_statistics(f);
  EXPECT_DOUBLE_EQ(s.exposed_area_fraction[0], 0.5);
  EXPECT_DOUBLE_EQ(s.exposed_area_fraction[1], 0.5);
  EXPECT_NEAR(s.surface_area_ratio, std::sqrt(1.25), 1e-12);
}

TEST(HeightField, HeightAtInterpolatesTheTwoTriangles) {
  rs::HeightField f = rs::make_flat(lambert(0.5), 4, 1.0);
  f.heights[0 * 4 + 1] = 1.0;  // node (1, 0)
  // On triangle (00, 10, 11) of cell (0, 0): z = z00 + (z10 - z00) u + (z11 - z10) v.
  EXPECT_NEAR(f.height_at(0.75, 0.25), 0.75 - 0.25, 1e-15);
  // On triangle (00, 11, 01): z = z00 + (z11 - z01) u + (z01 - z00) v = 0.
  EXPECT_NEAR(f.height_at(0.25, 0.75), 0.0, 1e-15);
  // Periodic.
  EXPECT_NEAR(f.height_at(4.75, -3.75), 0.5, 1e-15);
}

TEST(SurfaceFile, RoundTrip) {
  rs::HeightField f = rs::make_gaussian_slope_surface(lambert(0.8), 0.3, 32, 0.1, 7, 64);
  f.materials.push_back(lambert(0.1, "dark"));
  f.material[5] = 1;
  const std::string path = temp_path("roundtrip.json");
  rs::write_surface(f, path);
  const rs::HeightField g = rs::read_surface(path);
  ASSERT_EQ(g.nx, f.nx);
  ASSERT_EQ(g.ny, f.ny);
  EXPECT_DOUBLE_EQ(g.cell_size_mm, f.cell_size_mm);
  for (std::size_t k = 0; k < f.heights.size(); ++k) EXPECT_NEAR(g.heights[k], f.heights[k], 0.5e-4 + 1e-12);
  EXPECT_EQ(g.material, f.material);
  ASSERT_EQ(g.materials.size(), 2u);
  EXPECT_EQ(g.materials[1].name, "dark");
  EXPECT_EQ(g.materials[1].model, "lambert");
  EXPECT_DOUBLE_EQ(g.materials[1].parameters.at("albedo"), 0.1);
  std::filesystem::remove(path);
}

// The SURFACE file's material entries and statistics are the MaterialSpec and TextureStatistics JSON
// (the file keeps the statistics of its format: no height extremes, a note), fit paths made relative.
TEST(SurfaceFile, MaterialsAndStatisticsAsTheFileWritesThem) {
  rs::HeightField f = rs::make_gaussian_slope_surface(lambert(0.8), 0.3, 32, 0.1, 7, 64);
  rs::MaterialSpec fitted;
  fitted.name = "mastic";
  fitted.fit_path = (std::filesystem::path(temp_path("fits")) / "mastic.fit.json").string();
  fitted.fit_model = "lambert";
  f.materials.push_back(fitted);
  const rs::TextureStatistics s = rs::texture_statistics(f);
  const std::string path = temp_path("statistics.json");
  rs::write_surface(f, path, &s);
  std::ifstream in(path);
  const nlohmann::json file = nlohmann::json::parse(in);
  const nlohmann::json& written = file.at("statistics");
  EXPECT_EQ(written.at("mpd_mm"), s.mpd_mm);
  EXPECT_EQ(written.at("exposed_area_fraction"), nlohmann::json(s.exposed_area_fraction));
  for (const char* key : {"mean_height_mm", "min_height_mm", "max_height_mm"}) EXPECT_FALSE(written.contains(key));
  EXPECT_TRUE(written.contains("note"));
  EXPECT_EQ(s.to_json().at("max_height_mm"), s.max_height_mm);
  EXPECT_EQ(file.at("materials").at(0), f.materials[0].to_json());
  EXPECT_EQ(file.at("materials").at(1).at("fit"), "surface_test_fits/mastic.fit.json");
  EXPECT_EQ(fitted.to_json().at("fit"), fitted.fit_path);
  std::filesystem::remove(path);
}

TEST(SurfaceFile, BadFilesAreErrors) {
  const std::string path = temp_path("bad.json");
  {
    std::ofstream out(path);
    out << R"({"format": "roadbrdf-surface", "version": 1, "cell_size_mm": 0.1, "nx": 2, "ny": 2,
              "materials": [{"name": "a", "model": "lambert"}], "heights_mm": [0, 0, 0], "material": [0, 0, 0, 0]})";
  }
  EXPECT_THROW(rs::read_surface(path), roadbrdf::FileError);
  {
    std::ofstream out(path);
    out << R"({"format": "roadbrdf-surface", "version": 1, "cell_size_mm": 0.1, "nx": 2, "ny": 2,
              "materials": [{"name": "a", "model": "lambert"}], "heights_mm": [0, 0, 0, 0], "material": [0, 0, 0, 3]})";
  }
  EXPECT_THROW(rs::read_surface(path), roadbrdf::FileError);
  std::filesystem::remove(path);
}

TEST(PngPreview, WritesAValidSignatureAndSize) {
  const rs::HeightField f = rs::make_gaussian_slope_surface(lambert(0.8), 0.3, 32, 0.1, 7, 64);
  const std::string path = temp_path("preview.png");
  rs::write_preview_png(f, path);
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 33u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(bytes.substr(12, 4), "IHDR");
  EXPECT_EQ(static_cast<unsigned char>(bytes[19]), 32);  // width (big-endian, low byte)
  // Raw size 32 * (3*32 + 1) plus stored-block and zlib overhead.
  EXPECT_GT(bytes.size(), 32u * 97u);
  std::filesystem::remove(path);
}

// Exact traversal against brute-force marching along the ray with the interpolated height.
TEST(RayTraversal, MatchesBruteForceMarching) {
  const rs::HeightField f = rs::make_gaussian_slope_surface(lambert(0.8), 0.5, 48, 0.1, 3, 128);
  const rs::Renderer r(f, rs::load_materials(f, {550.0}), 1);
  roadbrdf::Rng rng(11);
  double zmax = -1e9;
  for (double z : f.heights) zmax = std::max(zmax, z);
  int hits = 0;
  for (int k = 0; k < 300; ++k) {
    const double theta = std::acos(rng.uniform()) * 0.999, phi = 2 * kPi * rng.uniform();
    const Vec3 d{-std::sin(theta) * std::cos(phi), -std::sin(theta) * std::sin(phi), -std::cos(theta)};
    const Vec3 o{rng.uniform() * 4.8, rng.uniform() * 4.8, zmax + 0.01};
    rs::Renderer::Hit hit;
    ASSERT_TRUE(r.intersect(o, d, hit));
    // Brute force: first t where the ray is below the surface, by steps of 1e-4 mm then bisection.
    const double step = 1e-4;
    double t = 0.0;
    auto below = [&](double tt) {
      const Vec3 p = o + tt * d;
      return p.z <= f.height_at(p.x, p.y);
    };
    while (!below(t + step)) t += step;
    double lo = t, hi = t + step;
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (below(mid) ? hi : lo) = mid;
    }
    EXPECT_NEAR(hit.t, hi, 1e-9) << "ray " << k;
    EXPECT_NEAR(hit.p.z, f.height_at(hit.p.x, hit.p.y), 1e-9);
    EXPECT_GT(hit.n.z, 0.0);
    ++hits;
  }
  EXPECT_EQ(hits, 300);
  // A ray going up from above the highest point escapes.
  rs::Renderer::Hit hit;
  EXPECT_FALSE(r.intersect(Vec3{1.0, 1.0, zmax + 0.01}, roadbrdf::normalize(Vec3{0.3, 0.2, 0.1}), hit));
}

// The traversal's empty-space skipping (blocks of HeightFieldTracer::kBlock cells) on periods that
// are not a multiple of the block (45: a narrower last block; 5: one block narrower than kBlock, which
// a ray re-enters as it wraps around), for rays starting outside the period, nearly horizontal ones,
// and secondary rays going up from just above a surface point (they hit a neighbouring slope or escape): the
// same first hit as brute-force marching along the ray, or none where marching escapes.
TEST(RayTraversal, MatchesBruteForceOnAnyPeriodAndDirection) {
  roadbrdf::Rng rng(29);
  for (const int n : {45, 5}) {
    rs::HeightField f = rs::make_flat(lambert(0.8), n, 0.1);
    if (n >= 32) {
      f = rs::make_gaussian_slope_surface(lambert(0.8), 0.6, n, 0.1, 5, 64);
    } else {  // a small period of random heights (the generator needs 32 cells)
      for (double& z : f.heights) z = 0.2 * rng.uniform();
    }
    const rs::Renderer r(f, rs::load_materials(f, {550.0}), 1);
    double zmax = -1e9;
    for (double z : f.heights) zmax = std::max(zmax, z);
    const double period = n * 0.1;
    // First t where the ray is below the surface (steps of 1e-4 mm, then bisection), or -1 when it
    // climbs above the highest point first.
    auto march = [&](const Vec3& o, const Vec3& d) {
      auto below = [&](double tt) {
        const Vec3 p = o + tt * d;
        return p.z <= f.height_at(p.x, p.y);
      };
      const double step = 1e-4;
      double t = 0.0;
      while (!below(t + step)) {
        t += step;
        if (d.z > 0.0 && o.z + t * d.z > zmax) return -1.0;
      }
      double lo = t, hi = t + step;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        (below(mid) ? hi : lo) = mid;
      }
      return hi;
    };
    int down = 0, up_hits = 0, up_escapes = 0;
    for (int k = 0; k < 200; ++k) {
      // Downward rays, zenith angles up to 89.4 deg, from anywhere in [-3, 4) periods.
      const double theta = std::acos(rng.uniform()) * 0.993, phi = 2 * kPi * rng.uniform();
      const Vec3 d{-std::sin(theta) * std::cos(phi), -std::sin(theta) * std::sin(phi), -std::cos(theta)};
      const Vec3 o{(7.0 * rng.uniform() - 3.0) * period, (7.0 * rng.uniform() - 3.0) * period, zmax + 0.01};
      rs::Renderer::Hit hit;
      ASSERT_TRUE(r.intersect(o, d, hit)) << "n " << n << " ray " << k;
      EXPECT_NEAR(hit.t, march(o, d), 1e-9) << "n " << n << " ray " << k;
      ++down;
      // From that hit, a ray going up at a random direction of the upper hemisphere.
      const double theta_up = std::acos(rng.uniform()) * 0.95, phi_up = 2 * kPi * rng.uniform();
      const Vec3 d_up{std::sin(theta_up) * std::cos(phi_up), std::sin(theta_up) * std::sin(phi_up), std::cos(theta_up)};
      // Raised 0.01 mm: marching by 1e-4 mm cannot resolve a ray grazing the facet it starts on.
      const Vec3 o_up{hit.p.x, hit.p.y, hit.p.z + 0.01};
      rs::Renderer::Hit up;
      const double t_up = march(o_up, d_up);
      if (r.intersect(o_up, d_up, up)) {
        EXPECT_NEAR(up.t, t_up, 1e-9) << "n " << n << " up ray " << k;
        ++up_hits;
      } else {
        EXPECT_EQ(t_up, -1.0) << "n " << n << " up ray " << k;
        ++up_escapes;
      }
    }
    EXPECT_EQ(down, 200);
    // Both outcomes occur, so both paths of the traversal are compared.
    EXPECT_GT(up_hits, 10) << n;
    EXPECT_GT(up_escapes, 10) << n;
  }
}

TEST(Generator, InvariantsDeterminismAndTargetMpd) {
  rs::SampleRecipe recipe;
  recipe.name = "test mix";
  recipe.matrix = lambert(0.05, "mastic");
  rs::GrainClass fine;
  fine.material = lambert(0.3, "2/4");
  fine.d_min_mm = 2;
  fine.d_max_mm = 4;
  fine.volume_fraction = 0.15;
  rs::GrainClass coarse;
  coarse.material = lambert(0.4, "4/6");
  coarse.d_min_mm = 4;
  coarse.d_max_mm = 6;
  coarse.volume_fraction = 0.2;
  recipe.classes = {fine, coarse};
  rs::GeneratorSettings s;
  s.size_mm = 16.0;
  s.cell_size_mm = 0.1;
  s.seed = 5;
  s.matrix_level = 0.5;
  const rs::GeneratedSample g = rs::generate_sample(recipe, s);
  EXPECT_EQ(g.field.nx, 160);
  EXPECT_DOUBLE_EQ(g.slab_thickness_mm, 6.0);
  // A reachable grading (0.35 of the slab): every class reaches its target (more in surface_packing_test).
  EXPECT_TRUE(g.targets_reached);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_GT(g.grain_count[k], 0);
    EXPECT_GE(g.achieved_volume_fraction[k], g.target_volume_fraction[k]);
  }
  const rs::TextureStatistics st = rs::texture_statistics(g.field);
  double sum = 0.0;
  for (double a : st.exposed_area_fraction) sum += a;
  EXPECT_NEAR(sum, 1.0, 1e-12);
  EXPECT_GT(st.exposed_area_fraction[1] + st.exposed_area_fraction[2], 0.05);
  EXPECT_GT(st.mpd_mm, 0.05);
  // Nothing below the matrix level; nothing above the slab.
  for (double z : g.field.heights) {
    EXPECT_GE(z, g.matrix_level_mm - 1e-12);
    EXPECT_LE(z, 6.0 + 1e-9);
  }
  // Deterministic.
  const rs::GeneratedSample g2 = rs::generate_sample(recipe, s);
  EXPECT_EQ(g2.field.heights, g.field.heights);
  // Target MPD by bisection on the matrix level.
  s.target_mpd_mm = 0.5 * st.mpd_mm;
  const rs::GeneratedSample g3 = rs::generate_sample(recipe, s);
  EXPECT_NEAR(rs::texture_statistics(g3.field).mpd_mm, 0.5 * st.mpd_mm, 1e-6);
  EXPECT_GT(g3.matrix_level_mm, g.matrix_level_mm);
  // An MPD above what the grains can give (the slab is 6 mm thick) is an error, not a clamp.
  s.target_mpd_mm = 50.0;
  try {
    rs::generate_sample(recipe, s);
    FAIL() << "no error for an unreachable MPD";
  } catch (const roadbrdf::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not reachable"), std::string::npos) << e.what();
  }
}

TEST(Generator, GaussianSlopeSurfaceHasTheRequestedRmsSlope) {
  const double sigma = 0.3;
  const rs::HeightField f = rs::make_gaussian_slope_surface(lambert(0.5), sigma, 64, 0.1, 2, 256);
  double s2 = 0.0;
  for (int j = 0; j < 64; ++j) {
    for (int i = 0; i < 64; ++i) {
      const double sx = (f.height(i + 1, j) - f.height(i, j)) / 0.1, sy = (f.height(i, j + 1) - f.height(i, j)) / 0.1;
      s2 += 0.5 * (sx * sx + sy * sy);
    }
  }
  EXPECT_NEAR(std::sqrt(s2 / (64.0 * 64.0)), std::tan(sigma), 1e-12);
}
