// Grain packing of the virtual sample (packing.h, generate.h): exact overlap test, non-overlap of the
// generated grains, achieved vs target volume fractions, class proportions, gradings -> textures.
#include <gtest/gtest.h>
#include "support/materials.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "roadbrdf/core/math.h"
#include "roadbrdf/core/random.h"
#include "roadbrdf/surface/generate.h"
#include "roadbrdf/surface/packing.h"

namespace rs = roadbrdf::surface;
using roadbrdf::kPi;

namespace {

using roadbrdf::test::lambert;

rs::SampleRecipe two_classes(double phi_fine, double phi_coarse) {
  rs::SampleRecipe r;
  r.name = "test";
  r.matrix = lambert(0.05, "mastic");
  rs::GrainClass fine, coarse;
  fine.material = lambert(0.3, "2/6");
  fine.d_min_mm = 2;
  fine.d_max_mm = 6;
  fine.volume_fraction = phi_fine;
  coarse.material = lambert(0.4, "6/10");
  coarse.d_min_mm = 6;
  coarse.d_max_mm = 10;
  coarse.volume_fraction = phi_coarse;
  r.classes = {fine, coarse};
  return r;
}

// Independent of packing.cpp: the implicit function sum_k ((R^T (p - centre))_k / s_k)^2 of an
// ellipsoid from its rotation columns and semi-axes, and points of its surface from the same.
double implicit(const rs::Ellipsoid& e, double px, double py, double pz) {
  const double d[3] = {px - e.x, py - e.y, pz - e.z};
  const double s[3] = {e.a, e.b, e.c};
  double q = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double t = e.rotation[0 * 3 + k] * d[0] + e.rotation[1 * 3 + k] * d[1] + e.rotation[2 * 3 + k] * d[2];
    q += (t / s[k]) * (t / s[k]);
  }
  return q;
}

// Smallest implicit value of `q` over a dense grid of surface points of `p` (n x 2n in theta, phi),
// p shifted by (sx, sy). Below 1: a point of p's surface lies inside q.
double min_implicit_over_surface(const rs::Ellipsoid& p, const rs::Ellipsoid& q, double sx, double sy, int n) {
  double best = 1e300;
  for (int i = 0; i < n; ++i) {
    const double th = kPi * (i + 0.5) / n;
    for (int j = 0; j < 2 * n; ++j) {
      const double ph = kPi * j / n;
      const double l[3] = {p.a * std::sin(th) * std::cos(ph), p.b * std::sin(th) * std::sin(ph), p.c * std::cos(th)};
      double w[3];
      for (int r = 0; r < 3; ++r)
        w[r] = p.rotation[r * 3] * l[0] + p.rotation[r * 3 + 1] * l[1] + p.rotation[r * 3 + 2] * l[2];
      best = std::min(best, implicit(q, p.x + sx + w[0], p.y + sy + w[1], p.z + w[2]));
    }
  }
  return best;
}

// Brute-force overlap: a surface point of one inside the other (either way). For convex bodies that
// overlap with positive volume one of the two holds; sampling may miss overlaps thinner than the grid.
bool sampled_overlap(const rs::Ellipsoid& p, const rs::Ellipsoid& q, double sx, double sy, int n) {
  rs::Ellipsoid ps = p;
  ps.x += sx;
  ps.y += sy;
  return min_implicit_over_surface(ps, q, 0.0, 0.0, n) < 1.0 || min_implicit_over_surface(q, ps, 0.0, 0.0, n) < 1.0;
}

rs::Mat3 rotation_from(roadbrdf::Rng& g) {
  // Gram-Schmidt on random vectors (independent of the library's quaternion construction).
  double v[3][3];
  double* x = &v[0][0];
  for (int k = 0; k < 9; k += 2) {
    const auto [z0, z1] = g.normal_pair();
    x[k] = z0;
    if (k + 1 < 9) x[k + 1] = z1;
  }
  for (int k = 0; k < 3; ++k) {
    for (int j = 0; j < k; ++j) {
      const double d = v[k][0] * v[j][0] + v[k][1] * v[j][1] + v[k][2] * v[j][2];
      for (int c = 0; c < 3; ++c) v[k][c] -= d * v[j][c];
    }
    const double n = std::sqrt(v[k][0] * v[k][0] + v[k][1] * v[k][1] + v[k][2] * v[k][2]);
    for (int c = 0; c < 3; ++c) v[k][c] /= n;
  }
  // Columns = v[k].
  return {v[0][0], v[1][0], v[2][0], v[0][1], v[1][1], v[2][1], v[0][2], v[1][2], v[2][2]};
}

}  // namespace

TEST(Packing, PerramWertheimMatchesClosedFormsForSpheresAndAlignedEllipsoids) {
  rs::Ellipsoid p, q;
  p.a = p.b = p.c = 1.0;
  q.a = q.b = q.c = 2.0;
  q.x = 3.0 * 0.999;  // spheres overlap iff the distance < r1 + r2 = 3
  EXPECT_TRUE(rs::ellipsoids_overlap(p, q));
  q.x = 3.0 * 1.001;
  EXPECT_FALSE(rs::ellipsoids_overlap(p, q));
  // Two ellipsoids with semi-axes (3, 1, 0.5) along x, y, z side by side along y: contact at 2.
  p = rs::Ellipsoid{};
  p.a = 3.0;
  p.b = 1.0;
  p.c = 0.5;
  q = p;
  q.y = 2.0 * 0.999;
  EXPECT_TRUE(rs::ellipsoids_overlap(p, q));
  q.y = 2.0 * 1.001;
  EXPECT_FALSE(rs::ellipsoids_overlap(p, q));
  // One rotated by 90 deg about z (its a along y): contact along y at 1 + 3 = 4.
  q.rotation = {0, -1, 0, 1, 0, 0, 0, 0, 1};
  q.y = 4.0 * 0.999;
  EXPECT_TRUE(rs::ellipsoids_overlap(p, q));
  q.y = 4.0 * 1.001;
  EXPECT_FALSE(rs::ellipsoids_overlap(p, q));
}

TEST(Packing, VolumeBelowAPlaneMatchesNumericalIntegration) {
  // A tilted ellipsoid cut by horizontal planes: the volume below, by midpoint integration over a
  // 200^3 grid of its bounding box, against the library's cap formula.
  roadbrdf::Rng g(5);
  rs::Ellipsoid e;
  e.a = 3.0;
  e.b = 2.0;
  e.c = 1.0;
  e.z = 0.7;
  e.rotation = rotation_from(g);
  const int n = 200;
  const double h = 2.0 * e.a / n;
  for (double z0 : {-1.5, 0.0, 0.7, 1.9}) {
    long inside = 0;
    for (int k = 0; k < n; ++k) {
      const double z = e.z - e.a + (k + 0.5) * h;
      if (z >= z0) continue;
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
          if (implicit(e, -e.a + (i + 0.5) * h, -e.a + (j + 0.5) * h, z) < 1.0) ++inside;
        }
      }
    }
    EXPECT_NEAR(rs::ellipsoid_volume_below(e, z0), inside * h * h * h, 0.01 * e.volume()) << z0;
  }
  EXPECT_NEAR(rs::ellipsoid_volume_below(e, 100.0), 4.0 / 3.0 * kPi * 6.0, 1e-12);
  EXPECT_EQ(rs::ellipsoid_volume_below(e, -100.0), 0.0);
}

TEST(Packing, PerramWertheimAgreesWithDenseSurfaceSampling) {
  // Random pairs near contact: "separated" must never have a surface point inside the other, and an
  // "overlap" must show one once both are scaled up by 1 % about their centres.
  roadbrdf::Rng g(11);
  int separated = 0, overlapping = 0;
  for (int trial = 0; trial < 200; ++trial) {
    rs::Ellipsoid p, q;
    p.a = 1.0 + 2.0 * g.uniform();
    p.b = p.a * (0.4 + 0.6 * g.uniform());
    p.c = p.b * (0.3 + 0.7 * g.uniform());
    q.a = 1.0 + 2.0 * g.uniform();
    q.b = q.a * (0.4 + 0.6 * g.uniform());
    q.c = q.b * (0.3 + 0.7 * g.uniform());
    p.rotation = rotation_from(g);
    q.rotation = rotation_from(g);
    const double ct = 2.0 * g.uniform() - 1.0, ph = 2.0 * kPi * g.uniform(), st = std::sqrt(1.0 - ct * ct);
    const double dist = (p.c + q.c) + g.uniform() * (p.a + q.a - p.c - q.c);
    q.x = dist * st * std::cos(ph);
    q.y = dist * st * std::sin(ph);
    q.z = dist * ct;
    if (rs::ellipsoids_overlap(p, q)) {
      ++overlapping;
      rs::Ellipsoid P = p, Q = q;
      P.a *= 1.01, P.b *= 1.01, P.c *= 1.01, Q.a *= 1.01, Q.b *= 1.01, Q.c *= 1.01;
      EXPECT_TRUE(sampled_overlap(P, Q, 0.0, 0.0, 200)) << "trial " << trial;
    } else {
      ++separated;
      EXPECT_FALSE(sampled_overlap(p, q, 0.0, 0.0, 200)) << "trial " << trial;
    }
  }
  EXPECT_GT(separated, 30);
  EXPECT_GT(overlapping, 30);
}

namespace {

// Pairwise independent non-overlap check of a generated grain list (periodic in x, y).
void expect_no_overlap(const std::vector<rs::Ellipsoid>& grains, double L, double T) {
  long close_pairs = 0;
  for (std::size_t i = 0; i < grains.size(); ++i) {
    const rs::Ellipsoid& p = grains[i];
    // Rotation orthonormal (else the implicit function above would not describe the same grain).
    for (int c1 = 0; c1 < 3; ++c1) {
      for (int c2 = 0; c2 < 3; ++c2) {
        double d = 0.0;
        for (int r = 0; r < 3; ++r) d += p.rotation[r * 3 + c1] * p.rotation[r * 3 + c2];
        ASSERT_NEAR(d, c1 == c2 ? 1.0 : 0.0, 1e-9);
      }
    }
    // Below the roller's plane z = T: the vertical half-extent from the semi-axes and the third row of R.
    const double hz = std::sqrt(p.a * p.a * p.rotation[6] * p.rotation[6] + p.b * p.b * p.rotation[7] * p.rotation[7] +
                                p.c * p.c * p.rotation[8] * p.rotation[8]);
    EXPECT_LE(p.z + hz, T + 1e-9);
    for (std::size_t j = i + 1; j < grains.size(); ++j) {
      const rs::Ellipsoid& q = grains[j];
      for (int sx = -1; sx <= 1; ++sx) {
        for (int sy = -1; sy <= 1; ++sy) {
          const double dx = p.x + sx * L - q.x, dy = p.y + sy * L - q.y, dz = p.z - q.z;
          const double rb = std::max({p.a, p.b, p.c}) + std::max({q.a, q.b, q.c});
          if (dx * dx + dy * dy + dz * dz >= rb * rb) continue;
          ++close_pairs;
          EXPECT_FALSE(sampled_overlap(p, q, sx * L, sy * L, 60)) << "grains " << i << " and " << j;
        }
      }
    }
  }
  EXPECT_GT(close_pairs, static_cast<long>(grains.size()));  // a dense packing: many near neighbours
}

// Grain volume fraction of the slab 0 <= z <= T by Monte Carlo point sampling (independent of the
// cap formula in packing.cpp); also returns its standard error.
std::vector<double> sampled_fractions(const std::vector<rs::Ellipsoid>& grains, std::size_t K, double L, double T,
                                      int points, double& sigma_max) {
  roadbrdf::Rng g(3);
  std::vector<long> hits(K, 0);
  for (int n = 0; n < points; ++n) {
    const double x = g.uniform() * L, y = g.uniform() * L, z = g.uniform() * T;
    for (const auto& e : grains) {
      const double r = std::max({e.a, e.b, e.c});
      if (std::fabs(z - e.z) >= r) continue;
      bool in = false;
      for (int sx = -1; sx <= 1 && !in; ++sx)
        for (int sy = -1; sy <= 1 && !in; ++sy) in = implicit(e, x + sx * L, y + sy * L, z) < 1.0;
      if (in) {
        ++hits[e.cls];
        break;
      }
    }
  }
  std::vector<double> f(K);
  sigma_max = 0.0;
  for (std::size_t k = 0; k < K; ++k) {
    f[k] = double(hits[k]) / points;
    sigma_max = std::max(sigma_max, std::sqrt(f[k] * (1.0 - f[k]) / points));
  }
  return f;
}

rs::GeneratorSettings settings(double size, std::uint64_t seed) {
  rs::GeneratorSettings s;
  s.size_mm = size;
  s.cell_size_mm = 0.2;
  s.seed = seed;
  return s;
}

}  // namespace

TEST(Packing, DenseGeneratedGrainsDoNotOverlap) {
  // A formulation-like grading that needs the deposition phase.
  const rs::GeneratedSample g = rs::generate_sample(two_classes(0.18, 0.40), settings(24.0, 4));
  EXPECT_TRUE(g.deposition);
  ASSERT_GT(g.grains.size(), 40u);
  expect_no_overlap(g.grains, 24.0, 10.0);
}

TEST(Packing, ReachableTargetsAreMetAndTheReportedFractionsAreTrue) {
  // Loose (random sequential addition) and dense (deposition) targets, both reachable: every class
  // reaches its target, exceeding it by at most its largest grain; the reported fractions agree with
  // point sampling of the grain list within 4 sigma.
  for (const auto& [fine, coarse, dense] : {std::tuple{0.06, 0.12, false}, std::tuple{0.14, 0.30, true}}) {
    const double L = 30.0, T = 10.0;
    const rs::GeneratedSample g = rs::generate_sample(two_classes(fine, coarse), settings(L, 7));
    EXPECT_TRUE(g.targets_reached);
    EXPECT_EQ(g.deposition, dense);
    EXPECT_TRUE(g.notes.empty());
    std::vector<double> largest(2, 0.0);
    for (const auto& e : g.grains) largest[e.cls] = std::max(largest[e.cls], e.volume() / (L * L * T));
    for (std::size_t k = 0; k < 2; ++k) {
      EXPECT_GE(g.achieved_volume_fraction[k], g.target_volume_fraction[k]);
      EXPECT_LE(g.achieved_volume_fraction[k], g.target_volume_fraction[k] + largest[k] + 1e-12);
    }
    double sigma = 0.0;
    const std::vector<double> f = sampled_fractions(g.grains, 2, L, T, 40000, sigma);
    for (std::size_t k = 0; k < 2; ++k) EXPECT_NEAR(f[k], g.achieved_volume_fraction[k], 4.0 * sigma + 1e-3) << k;
  }
}

TEST(Packing, UnreachableTargetsScaleAllClassesTogether) {
  // Targets above a dense packing: not reached, reported, and each class at the same fraction of its
  // target within one grain (the class furthest behind is always the next one placed).
  const double L = 40.0, T = 10.0;
  const rs::GeneratedSample g = rs::generate_sample(two_classes(0.25, 0.45), settings(L, 2));
  EXPECT_FALSE(g.targets_reached);
  ASSERT_EQ(g.notes.size(), 1u);
  EXPECT_NE(g.notes[0].find("jammed"), std::string::npos);
  EXPECT_NE(g.field.description.find("NOT reached"), std::string::npos);
  std::vector<double> largest(2, 0.0);
  for (const auto& e : g.grains) {
    largest[e.cls] = std::max(largest[e.cls], e.volume() / (L * L * T) / g.target_volume_fraction[e.cls]);
  }
  const double r0 = g.achieved_volume_fraction[0] / g.target_volume_fraction[0];
  const double r1 = g.achieved_volume_fraction[1] / g.target_volume_fraction[1];
  EXPECT_LT(r0, 1.0);
  EXPECT_LT(r1, 1.0);
  EXPECT_GT(r0, 0.6);  // a dense packing, not a random-sequential-addition jam (~0.3 of the slab)
  EXPECT_LE(std::fabs(r0 - r1), std::max(largest[0], largest[1]));
  // The deposit reaches below the slab here: the reported fractions count only the part of each grain
  // inside it (point sampling of the grain list within 4 sigma).
  double sigma = 0.0;
  const std::vector<double> f = sampled_fractions(g.grains, 2, L, T, 40000, sigma);
  for (std::size_t k = 0; k < 2; ++k) EXPECT_NEAR(f[k], g.achieved_volume_fraction[k], 4.0 * sigma) << k;
}

TEST(Packing, GradingsGiveDifferentTexturesAndDeterministicSamples) {
  // Same seed, two gradings: different height fields; the coarse class covers a larger share of the
  // exposed grain area where its share of the grain volume is larger.
  const rs::GeneratedSample coarse_rich = rs::generate_sample(two_classes(0.12, 0.42), settings(30.0, 1));
  const rs::GeneratedSample fine_rich = rs::generate_sample(two_classes(0.36, 0.18), settings(30.0, 1));
  EXPECT_NE(coarse_rich.field.heights, fine_rich.field.heights);
  const auto a = rs::texture_statistics(coarse_rich.field).exposed_area_fraction;
  const auto b = rs::texture_statistics(fine_rich.field).exposed_area_fraction;
  EXPECT_GT(a[2] / a[1], 1.5 * b[2] / b[1]);
  const rs::GeneratedSample again = rs::generate_sample(two_classes(0.12, 0.42), settings(30.0, 1));
  EXPECT_EQ(again.field.heights, coarse_rich.field.heights);
  EXPECT_EQ(again.field.material, coarse_rich.field.material);
}

TEST(Packing, ProgressIsTheShareOfTheTargetVolumesAndChangesNothing) {
  // packing.h: random sequential addition reports 0..500, deposition (after a jam) 500..1000, in
  // thousandths of the target volume placed in the layer; reporting does not change the sample.
  for (const auto& [fine, coarse, dense] : {std::tuple{0.06, 0.12, false}, std::tuple{0.14, 0.30, true}}) {
    std::vector<std::size_t> done;
    rs::GeneratorSettings s = settings(30.0, 7);
    s.progress = [&](std::size_t d, std::size_t total) {
      EXPECT_EQ(total, 1000u);
      done.push_back(d);
    };
    const rs::GeneratedSample with = rs::generate_sample(two_classes(fine, coarse), s);
    const rs::GeneratedSample without = rs::generate_sample(two_classes(fine, coarse), settings(30.0, 7));
    EXPECT_EQ(with.grains.size(), without.grains.size());
    EXPECT_EQ(with.field.heights, without.field.heights);
    ASSERT_GE(done.size(), 2u);
    EXPECT_TRUE(std::is_sorted(done.begin(), done.end()));
    EXPECT_EQ(done.back(), 1000u);
    // Before the final report: below half without deposition; past half with it.
    EXPECT_EQ(done[done.size() - 2] > 500, dense) << done[done.size() - 2];
  }
}
