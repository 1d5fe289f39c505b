// Real data: the CUReT concrete samples (Dana et al., ACM TOG 18(1) 1999; sample numbers 45, 49, 50
// are "Concrete_a", "Concrete_b", "Concrete_c" in the CUReT sample list), grey BRDF at 205
// geometries, bundled in data/third-party/curet. Oren-Nayar and a diffuse + specular composite must
// converge and fit better than a Lambertian surface (lower RMSE and lower BIC).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "roadbrdf/core/data_path.h"
#include "roadbrdf/fitting/fit.h"
#include "roadbrdf/io/curet.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {
namespace {

const std::string kCuret = roadbrdf::data_directory() + "/third-party/curet/";

class CuretConcrete : public ::testing::TestWithParam<int> {};

TEST_P(CuretConcrete, RoughDiffuseAndSpecularModelsBeatLambert) {
  const std::string abrdf = kCuret + "abrdf.dat", table = kCuret + "table.txt";
  if (!std::filesystem::exists(abrdf)) GTEST_SKIP() << "CUReT data not bundled";
  CuretReadOptions read_options;
  read_options.warn = [](const std::string&) {};
  const SpectralDataset data = read_curet(abrdf, table, GetParam(), read_options);
  ASSERT_GT(data.geometry_count(), 100u);

  auto lambert = make_model("lambert");
  auto on = make_model("oren-nayar");
  auto composite = make_model("oren-nayar+torrance-sparrow");
  const FitResult fl = fit_model(*lambert, data, FitOptions{});
  FitOptions on_options;
  on_options.multistart = 4;
  const FitResult fo = fit_model(*on, data, on_options);
  FitOptions c_options;
  // Weights are not separately identifiable from albedo and k_s: hold them at 1.
  c_options.fixed = {{"oren-nayar.weight", 1.0}, {"torrance-sparrow.weight", 1.0}};
  c_options.start = {{"torrance-sparrow.ks", 0.1}};
  c_options.multistart = 6;
  const FitResult fc = fit_model(*composite, data, c_options);

  for (const FitResult* f : {&fl, &fo, &fc}) {
    const WavelengthFit& w = f->wavelengths[0];
    std::printf("CUReT sample %d  %-28s rmse %.5f sr^-1  rel %.3f  R2 %.3f  BIC %.1f  converged %d  at bounds:",
                GetParam(), f->model.c_str(), w.rmse, w.relative_rmse, w.r_squared, w.bic, int(w.converged));
    for (const auto& b : w.at_bounds) std::printf(" %s", b.c_str());
    std::printf("\n  parameters:");
    for (std::size_t k = 0; k < w.parameters.size(); ++k) {
      std::printf(" %s=%.4g(+-%.2g)", f->parameter_names[k].c_str(), w.parameters[k], w.standard_errors[k]);
    }
    std::printf("\n");
    EXPECT_TRUE(w.converged) << f->model << ": " << w.status;
  }
  EXPECT_LT(fo.wavelengths[0].rmse, fl.wavelengths[0].rmse);
  EXPECT_LT(fo.wavelengths[0].bic, fl.wavelengths[0].bic);
  EXPECT_LT(fc.wavelengths[0].rmse, fl.wavelengths[0].rmse);
  EXPECT_LT(fc.wavelengths[0].bic, fl.wavelengths[0].bic);
  // The composite contains Oren-Nayar (k_s = 0): with a good optimiser it cannot be worse.
  EXPECT_LE(fc.wavelengths[0].rmse, fo.wavelengths[0].rmse * (1.0 + 1e-6));
}

INSTANTIATE_TEST_SUITE_P(Concrete, CuretConcrete, ::testing::Values(45, 49, 50));

}  // namespace
}  // namespace roadbrdf
