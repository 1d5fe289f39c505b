// The per-wavelength solver on problems whose bound-constrained optimum is known in closed form:
// noise-free data made from known parameters are recovered (cost 0), also when a parameter of the
// data lies on a bound of its fitting range and the start lies far from it; and where the data ask
// for an amplitude beyond its bound, the optimum is the bound itself with the cost of the model
// there, both computed in the test from the data.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "roadbrdf/fitting/fit.h"
#include "roadbrdf/models/registry.h"
#include "synthetic.h"

namespace roadbrdf {
namespace {

bool on_bound(const WavelengthFit& f, const std::string& flag) {
  return std::find(f.at_bounds.begin(), f.at_bounds.end(), flag) != f.at_bounds.end();
}

// Hapke (HG, SHOE, 2002 H) with B0 = 1, the upper bound of its fitting range, from the plain start
// of a user's loop (w 0.5, b0 0.1, h 0.05, xi 0), without the amplitude solve and warm start: the
// iterates meet the bound on the way and must slide along it to the data's parameters.
TEST(FitSmallSolver, RecoversNoiseFreeHapkeWithB0OnItsUpperBound) {
  auto model = make_model("hapke", {{"h_function", "hapke2002"}, {"phase", "hg"}});
  const ModelDescription& desc = model->description();
  const std::vector<double> wl = {450.0, 550.0, 650.0};
  const std::vector<double> w_of = {0.35, 0.6, 0.85};
  std::vector<double> truth = desc.default_parameters();
  const std::size_t iw = *desc.parameter_index("w"), ib0 = *desc.parameter_index("b0"), ih = *desc.parameter_index("h"),
                    ixi = *desc.parameter_index("xi");
  truth[ib0] = 1.0;
  truth[ih] = 0.08;
  truth[ixi] = -0.3;
  const SpectralDataset data = test::synthetic_dataset(
      *model, test::test_grid(6, 6, 7), wl,
      [&](std::size_t w) {
        std::vector<double> p = truth;
        p[iw] = w_of[w];
        return p;
      },
      0.0, 0.0, 1);
  FitOptions o;
  o.start = {{"w", 0.5}, {"b0", 0.1}, {"h", 0.05}, {"xi", 0.0}};
  o.solve_linear = false;
  o.warm_start = false;
  const FitResult r = fit_model(*model, data, o);
  ASSERT_EQ(r.wavelengths.size(), 3u);
  for (std::size_t w = 0; w < 3; ++w) {
    const WavelengthFit& f = r.wavelengths[w];
    SCOPED_TRACE(wl[w]);
    EXPECT_TRUE(f.converged) << f.status;
    EXPECT_NEAR(f.parameters[iw], w_of[w], 1e-6);
    EXPECT_NEAR(f.parameters[ib0], 1.0, 1e-6);
    EXPECT_NEAR(f.parameters[ih], 0.08, 1e-5);
    EXPECT_NEAR(f.parameters[ixi], -0.3, 1e-6);
    EXPECT_LT(f.rmse, 1e-9);
    EXPECT_TRUE(on_bound(f, "b0=upper"));
  }
}

// Oren-Nayar data of smooth facets (sigma = 0, the lower bound) from sigma 0.5: the solver must
// stop on the bound with the albedo of the data. Oren-Nayar's A and B terms depend on sigma^2
// (Oren & Nayar 1994, eq. 30): the cost rises only as sigma^4 near 0, so sigma is resolved to about
// the fourth root of the cost's resolution; 1e-5 is still far below the start 0.5.
TEST(FitSmallSolver, RecoversNoiseFreeOrenNayarWithSigmaOnItsLowerBound) {
  auto model = make_model("oren-nayar");
  const ModelDescription& desc = model->description();
  const std::size_t ia = *desc.parameter_index("albedo"), is = *desc.parameter_index("sigma");
  std::vector<double> truth = desc.default_parameters();
  truth[ia] = 0.42;
  truth[is] = 0.0;
  const SpectralDataset data = test::synthetic_dataset(
      *model, test::test_grid(), {550.0}, [&](std::size_t) { return truth; }, 0.0, 0.0, 1);
  FitOptions o;
  o.start = {{"albedo", 0.8}, {"sigma", 0.5}};
  o.solve_linear = false;
  const WavelengthFit f = fit_model(*model, data, o).wavelengths.at(0);
  EXPECT_TRUE(f.converged) << f.status;
  EXPECT_NEAR(f.parameters[ia], 0.42, 1e-7);
  EXPECT_NEAR(f.parameters[is], 0.0, 1e-5);
  EXPECT_LT(f.rmse, 1e-9);
}

// Lambert f = rho / pi on data asking for rho > 1: the cost 1/2 sum (rho/pi - y)^2 is a convex
// parabola in rho whose minimum pi mean(y) lies beyond the bound, so the optimum on [0, 1] is rho = 1
// exactly, with the cost of rho = 1 (summed here from the data).
TEST(FitSmallSolver, AmplitudeBeyondItsBoundStopsOnTheBoundWithTheClosedFormCost) {
  auto model = make_model("lambert");
  const std::vector<Geometry> grid = test::test_grid();
  SpectralDataset data;
  data.geometries = grid;
  data.wavelengths = {550.0};
  double mean = 0.0;
  for (std::size_t g = 0; g < grid.size(); ++g) {
    data.brdf.push_back((1.3 + 0.05 * std::sin(3.0 * static_cast<double>(g))) / std::numbers::pi);
    mean += data.brdf.back() / static_cast<double>(grid.size());
  }
  ASSERT_GT(std::numbers::pi * mean, 1.0);
  double cost_at_bound = 0.0;
  for (double y : data.brdf) cost_at_bound += 0.5 * (1.0 / std::numbers::pi - y) * (1.0 / std::numbers::pi - y);
  FitOptions o;
  o.start = {{"albedo", 0.3}};
  o.solve_linear = false;
  const WavelengthFit f = fit_model(*model, data, o).wavelengths.at(0);
  EXPECT_TRUE(f.converged) << f.status;
  EXPECT_DOUBLE_EQ(f.parameters.at(0), 1.0);
  EXPECT_NEAR(f.cost, cost_at_bound, 1e-12 * cost_at_bound);
  EXPECT_TRUE(on_bound(f, "albedo=upper"));
}

}  // namespace
}  // namespace roadbrdf
