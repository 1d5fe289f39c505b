// The tabulated exact H function (models/hapke_h_table.h) against the direct quadrature h_exact
// (models/hapke_h_function.h), which is itself checked against independent references (bundled table,
// Nystrom solution, moment identities) in hapke_test.cpp; those references are applied to
// h_tabulated there too. Here:
//   - a dense (x, w) grid not aligned with the table (log- and linearly spaced x down to 1e-14,
//     w uniform and w = 1 - 10^-k up to w = 1), including both sides of every panel boundary;
//   - the derivative dH/dw against the derivative of the quadrature (automatic differentiation of
//     h_exact, an independent computation) and against central differences of h_tabulated itself;
//   - the fallback outside the table, the convention at w = 1, and concurrent first use.
#include "roadbrdf/models/hapke_h_table.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>
#include <thread>
#include <vector>

#include "roadbrdf/models/registry.h"

namespace roadbrdf {
namespace {

std::vector<double> grid_x() {
  std::vector<double> x;
  for (int i = 1; i <= 300; ++i) x.push_back((i - 0.3183) / 300.0);                        // linear, not at nodes
  for (int i = 0; i <= 300; ++i) x.push_back(std::pow(10.0, -14.0 * i / 300.0 - 0.0123));  // log
  for (int k = 0; k <= hapke::kHTableOctaves; ++k) {  // both sides of each octave boundary
    const double b = std::ldexp(1.0, -k);
    x.push_back(b);
    x.push_back(std::nextafter(b, 0.0));
    x.push_back(std::nextafter(b, 2.0));
  }
  x.push_back(1.0);
  return x;
}

std::vector<double> grid_w() {
  std::vector<double> w;
  for (int i = 0; i <= 120; ++i) w.push_back((i + 0.2718 * (i % 2)) / 121.0);
  for (int k = 1; k <= 64; ++k) w.push_back(1.0 - std::pow(10.0, -0.25 * k));  // w -> 1
  for (int j = 0; j <= hapke::kHTableGammaPanels; ++j) {                       // gamma panel boundaries
    const double gamma = double(j) / hapke::kHTableGammaPanels;
    w.push_back(1.0 - gamma * gamma);
    w.push_back(1.0 - sqr(std::nextafter(gamma, 2.0)));
  }
  w.push_back(1.0);
  return w;
}

TEST(HapkeHTable, MatchesTheDirectQuadratureOnADenseGrid) {
  // Stated accuracy (models/hapke_h_function.h): relative difference < 1e-13 for w <= 1 - 1e-5, and
  // < 5e-11 up to w = 1, where the quadrature itself is only accurate to ~2e-11 (its error, not the
  // table's, dominates there).
  double worst = 0.0, worst_near_one = 0.0;
  for (double w : grid_w()) {
    if (w < 0.0 || w > 1.0) continue;
    for (double x : grid_x()) {
      const double direct = hapke::h_exact(x, w);
      const double table = hapke::h_tabulated(x, w);
      const double error = std::fabs(table / direct - 1.0);
      if (w <= 1.0 - 1e-5) {
        worst = std::fmax(worst, error);
        EXPECT_LT(error, 1e-13) << "x=" << x << " w=" << w;
      } else {
        worst_near_one = std::fmax(worst_near_one, error);
        EXPECT_LT(error, 5e-11) << "x=" << x << " w=" << w;
      }
    }
  }
  std::ostringstream report;
  report << std::scientific << std::setprecision(2) << worst << " (w <= 1 - 1e-5), " << worst_near_one << " (w -> 1)";
  RecordProperty("worst_relative_error", report.str());
}

TEST(HapkeHTable, DerivativeMatchesTheQuadratureAndFiniteDifferences) {
  using Jet = ceres::Jet<double, 2>;
  for (double w : {0.013, 0.2, 0.5, 0.77, 0.9, 0.99, 0.9999}) {
    for (double x : {1e-9, 0.003, 0.02, 0.3, 0.61, 1.0}) {
      const Jet direct = hapke::h_exact(x, Jet(w, 1));
      const Jet table = hapke::h_tabulated(x, Jet(w, 1));
      EXPECT_EQ(table.a, hapke::h_tabulated(x, w));  // same value on the double and Jet paths
      EXPECT_EQ(table.v[0], 0.0);
      // dH/dw = (dH/dgamma) / (-2 gamma) grows like 1/sqrt(1 - w), and so does the absolute error of
      // the interpolant's derivative (~1e-13 in dH/dgamma).
      const double gamma = std::sqrt(1.0 - w);
      EXPECT_NEAR(table.v[1], direct.v[1], 1e-9 * std::fabs(direct.v[1]) + 1e-12 / gamma) << "x=" << x << " w=" << w;
      // Central differences: truncation ~ step^2, rounding ~ 1e-16 H / step.
      const double step = 1e-6 * gamma;
      const double fd = (hapke::h_tabulated(x, w + step) - hapke::h_tabulated(x, w - step)) / (2.0 * step);
      EXPECT_NEAR(table.v[1], fd, 1e-6 * std::fabs(fd) + 1e-15 / step) << "x=" << x << " w=" << w;
    }
  }
}

TEST(HapkeHTable, EdgesConventionsAndFallback) {
  using Jet = ceres::Jet<double, 1>;
  // w = 1: derivative 0 by convention (as sqrt(1 - w) in the closed forms), value finite.
  const Jet at_one = hapke::h_tabulated(0.5, Jet(1.0, 0));
  EXPECT_TRUE(std::isfinite(at_one.a));
  EXPECT_EQ(at_one.v[0], 0.0);
  // Below the table (x < 2^-40) and outside [0, 1] in w: the direct quadrature, bit for bit.
  for (double x : {1e-300, 1e-13, 0.5 * std::ldexp(1.0, -hapke::kHTableOctaves)}) {
    EXPECT_EQ(hapke::h_tabulated(x, 0.7), hapke::h_exact(x, 0.7)) << x;
  }
  EXPECT_EQ(hapke::h_tabulated(0.4, -1e-3), hapke::h_exact(0.4, -1e-3));
  EXPECT_EQ(hapke::h_tabulated(0.0, 0.5), 1.0);
  // Continuity across the lower end of the table.
  const double edge = std::ldexp(1.0, -hapke::kHTableOctaves);
  EXPECT_NEAR(hapke::h_tabulated(edge, 0.95), hapke::h_tabulated(std::nextafter(edge, 0.0), 0.95), 1e-13);
}

TEST(HapkeHTable, ConcurrentFirstUseGivesTheSameValues) {
  // Blocks are built on first use; several threads racing on the same blocks must see identical values.
  const std::vector<double> xs = {0.011, 0.23, 0.77, 1.0};
  const std::vector<double> ws = {0.031, 0.52, 0.93, 0.9993};
  std::vector<std::vector<double>> results(4);
  std::vector<std::thread> threads;
  for (int k = 0; k < 4; ++k) {
    threads.emplace_back([&, k] {
      for (double w : ws) {
        for (double x : xs) results[k].push_back(hapke::h_tabulated(x, w));
      }
    });
  }
  for (std::thread& t : threads) t.join();
  for (int k = 1; k < 4; ++k) EXPECT_EQ(results[k], results[0]);
  std::size_t i = 0;
  for (double w : ws) {
    for (double x : xs) EXPECT_NEAR(results[0][i++], hapke::h_exact(x, w), 1e-12 * hapke::h_exact(x, w));
  }
}

TEST(HapkeHTable, ModelPathsAgreeBitForBit) {
  // Single, batch (several parameter sets) and prepared paths of the "hapke" model all use the table,
  // so they agree exactly; the gradient paths agree exactly with each other and, as ceres::Jet
  // arithmetic rounds differently from double (e.g. a/b as a * (1/b)), to 1e-15 with the value paths.
  const auto model = make_model("hapke");
  const std::vector<double> params = {0.37, 0.4, 0.06, 0.2, 0.9991, 0.1, 0.3, -0.4};
  std::vector<Geometry> geometries;
  for (double ti : {0.0, 23.0, 61.0, 89.0}) {
    for (double tr : {5.0, 45.0, 80.0}) geometries.push_back(geometry_from_degrees(ti, 0.0, tr, 150.0));
  }
  std::vector<double> batch(geometries.size() * 2), values(geometries.size()), jacobian(geometries.size() * 4);
  model->evaluate_batch(geometries.data(), geometries.size(), params.data(), 2, batch.data());
  const auto prepared = model->prepare(geometries.data(), geometries.size());
  for (int s = 0; s < 2; ++s) {
    const double* p = params.data() + 4 * s;
    model->evaluate_prepared(*prepared, p, values.data());
    for (std::size_t n = 0; n < geometries.size(); ++n) {
      const double single = model->evaluate(p, geometries[n]);
      EXPECT_EQ(batch[n * 2 + s], single);
      EXPECT_EQ(values[n], single);
    }
    model->evaluate_prepared_with_gradient(*prepared, p, values.data(), jacobian.data());
    for (std::size_t n = 0; n < geometries.size(); ++n) {
      std::vector<double> gradient(4);
      const double f = model->evaluate_with_gradient(p, geometries[n], gradient.data());
      EXPECT_EQ(values[n], f);
      for (int k = 0; k < 4; ++k) EXPECT_EQ(jacobian[n * 4 + k], gradient[k]);
      EXPECT_NEAR(f, model->evaluate(p, geometries[n]), 1e-15 * f);
    }
  }
}

// The table reduced to one albedo (h_table_series, the path tracer's per-wavelength H): the same
// interpolant summed in another order, so within a few units in the last place of h_table_evaluate,
// and within the table's own accuracy of the quadrature.
TEST(HapkeHTable, SeriesAtOneAlbedoMatchesTheTable) {
  std::vector<double> series(hapke::kHTableSeriesSize);
  double worst = 0.0;
  for (double w : grid_w()) {
    const double gamma = std::sqrt(1.0 - w);
    hapke::h_table_series(gamma, series.data());
    for (double x : grid_x()) {
      hapke::HTablePoint point;
      ASSERT_EQ(hapke::h_table_point(x, point), hapke::h_table_covers(x, 0.5)) << x;  // x only
      if (!hapke::h_table_covers(x, w)) continue;
      const double table = hapke::h_table_evaluate(x, gamma, nullptr);
      const double value = hapke::h_series_evaluate(series.data(), point);
      worst = std::max(worst, std::fabs(value - table) / table);
      ASSERT_NEAR(value, table, 1e-14 * table) << "x " << x << " w " << w;
    }
  }
  EXPECT_GT(worst, 0.0);  // the order differs: not the same computation
  hapke::HTablePoint point;
  EXPECT_FALSE(hapke::h_table_point(0.0, point));
  EXPECT_FALSE(hapke::h_table_point(std::nextafter(1.0, 2.0), point));
  EXPECT_FALSE(hapke::h_table_point(std::ldexp(1.0, -hapke::kHTableOctaves - 1), point));
}

// The model's evaluator of fixed parameter sets (model.h FixedSetEvaluator, used by the renderer)
// against evaluate_batch, for every phase function, at geometries including mu = 0 and grazing ones
// (fallback to operator()), and with w at both ends; the approximate H functions take the generic path
// (bit for bit).
TEST(HapkeHTable, FixedSetsMatchTheBatchEvaluation) {
  std::vector<Geometry> geometries;
  for (double ti : {0.0, 1e-3, 23.0, 61.0, 89.0, 89.999999, 90.0}) {
    for (double tr : {0.0, 5.0, 45.0, 80.0, 89.9999, 90.0}) {
      for (double dp : {0.0, 37.0, 150.0, 180.0}) geometries.push_back(geometry_from_degrees(ti, 0.0, tr, dp));
    }
  }
  struct Case {
    std::map<std::string, std::string> options;
    std::vector<double> params;  // several sets
  };
  // 37 sets: more than two of the evaluator's chunks of 16, one of them (w = 1.2) outside the table.
  std::vector<double> many_sets;
  for (int s = 0; s < 37; ++s) {
    const double w = s == 20 ? 1.2 : 0.02 + 0.97 * s / 36.0;
    many_sets.insert(many_sets.end(), {w, 0.03 * (s % 7), 0.01 + 0.05 * (s % 5), -0.6 + 0.033 * s});
  }
  const std::vector<Case> cases = {
      {{}, {0.37, 0.4, 0.06, 0.2, 0.9991, 0.1, 0.3, -0.4, 0.0, 0.0, 0.05, 0.0}},
      {{{"phase", "legendre"}}, {0.5, 0.2, 0.1, 0.3, 0.4, 1.0, 0.0, 0.05, -0.2, 0.1, 0.02, 1.0, 1.0, 0.5, 0.9}},
      {{{"phase", "hg2"}}, {0.8, 0.3, 0.2, 0.4, 0.5, 0.123, 0.0, 0.05, 0.9, -1.0, 0.999999, 1.0, 2.0, 0.1, 0.2}},
      {{{"h_function", "hapke2002"}}, {0.37, 0.4, 0.06, 0.2, 0.9991, 0.1, 0.3, -0.4, 0.6, 0.0, 0.05, 0.0}},
      {{}, many_sets},
  };
  for (const Case& c : cases) {
    const auto model = make_model("hapke", c.options);
    const std::size_t np = model->parameter_count(), sets = c.params.size() / np;
    ASSERT_EQ(sets * np, c.params.size());
    const auto fixed = model->fixed_sets(c.params.data(), sets);
    std::vector<double> batch(sets), value(sets);
    int reordered = 0;  // values not bit for bit those of the batch: the series path was taken
    for (const Geometry& g : geometries) {
      model->evaluate_batch(&g, 1, c.params.data(), sets, batch.data());
      fixed->evaluate(g, value.data());
      for (std::size_t s = 0; s < sets; ++s) {
        if (std::isnan(batch[s])) {
          EXPECT_TRUE(std::isnan(value[s])) << "set " << s;  // w = 1.2: no H, evaluated by operator()
        } else if (c.options.count("h_function")) {
          EXPECT_EQ(value[s], batch[s]);
        } else {
          // Rounding of H is relative to H(mu0) H(mu) <= 9 (H <= 3), which cancels against the -1 of
          // the bracket where H -> 1 (mu -> 0): the tolerance is relative to that term, w <= 1.
          const double mu_sum = std::max(g.cos_theta_i(), 0.0) + std::max(g.cos_theta_r(), 0.0);
          const double scale = 10.0 / (4.0 * kPi * std::max(mu_sum, 1e-9));
          reordered += value[s] != batch[s];
          EXPECT_NEAR(value[s], batch[s], 1e-14 * (std::fabs(batch[s]) + scale))
              << "theta_i " << g.theta_i << " theta_r " << g.theta_r << " set " << s;
        }
      }
    }
    if (!c.options.count("h_function")) {
      EXPECT_GT(reordered, 0);
    }
  }
}

// dH/dx of the interpolant (used at the roughness option's effective cosines) against central
// differences of the direct quadrature, and the value and dH/dgamma unchanged.
TEST(HapkeHTable, SlopeInTheCosineMatchesFiniteDifferencesOfTheQuadrature) {
  for (double w : {0.1, 0.6, 0.95, 0.999}) {
    const double gamma = std::sqrt(1.0 - w);
    for (double x : {1e-6, 0.003, 0.05, 0.3, 0.5, 0.77, 0.999}) {
      double dh_dx = 0.0, dh_dgamma = 0.0, dh_dgamma_alone = 0.0;
      const double value = hapke::h_table_evaluate_slopes(x, gamma, &dh_dx, &dh_dgamma);
      EXPECT_EQ(value, hapke::h_table_evaluate(x, gamma, &dh_dgamma_alone));
      EXPECT_EQ(dh_dgamma, dh_dgamma_alone);
      const double step = 1e-5 * x;
      const double difference = (hapke::h_exact(x + step, w) - hapke::h_exact(x - step, w)) / (2.0 * step);
      // The interpolant's slope: within 1e-6 relative for x >= 1e-3, 1e-5 below (measured 6.5e-6 at x = 1e-6).
      const double tolerance = x >= 1e-3 ? 1e-6 : 1e-5;
      EXPECT_NEAR(dh_dx, difference, tolerance * std::fabs(difference)) << "w " << w << " x " << x;
    }
  }
}

}  // namespace
}  // namespace roadbrdf
