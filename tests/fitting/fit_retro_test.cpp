// Real data: two retroreflective tapes measured on a gonioreflectometer (ALTA data files,
// data/third-party/retroreflective). Retro-Phong (Spieringhs et al. 2023) and Lafortune lobes
// (Lafortune et al. 1997) must converge, and fit better than a Lambertian surface.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "roadbrdf/core/data_path.h"
#include "roadbrdf/fitting/fit.h"
#include "roadbrdf/io/alta.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {
namespace {

class RetroTape : public ::testing::TestWithParam<const char*> {};

TEST_P(RetroTape, RetroModelsConvergeAndBeatLambert) {
  const std::string path = roadbrdf::data_directory() + "/third-party/retroreflective/" + GetParam();
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "retroreflective data not bundled";
  AltaReadOptions ro;
  ro.wavelength_nm = 550.0;
  ro.exclude_grazing = true;
  ro.assumed_output = "INV_STERADIAN_COSINE_FACTOR";  // data/ATTRIBUTION.md: ALTA output is BRDF x cos
  ro.average_duplicates = true;
  ro.warn = [](const std::string&) {};
  const SpectralDataset data = read_alta(path, ro);
  auto lambert = make_model("lambert");
  const FitResult fl = fit_model(*lambert, data, FitOptions{});
  for (const char* name : {"retro-phong", "lafortune"}) {
    auto model = make_model(name);
    FitOptions o;
    o.multistart = 8;
    o.loss = FitLoss::kLog;  // the retro peak spans orders of magnitude
    const FitResult f = fit_model(*model, data, o);
    FitOptions ol;
    ol.loss = FitLoss::kLog;
    const FitResult fl_log = fit_model(*lambert, data, ol);
    const WavelengthFit& w = f.wavelengths[0];
    std::printf(
        "%s  %-12s n=%zu rmse %.4g sr^-1 (lambert %.4g)  log-chi2 %.4g (lambert %.4g)  converged %d  at bounds:",
        GetParam(), name, w.points, w.rmse, fl.wavelengths[0].rmse, w.chi2, fl_log.wavelengths[0].chi2,
        int(w.converged));
    for (const auto& b : w.at_bounds) std::printf(" %s", b.c_str());
    std::printf("\n  parameters:");
    for (std::size_t k = 0; k < w.parameters.size(); ++k) {
      std::printf(" %s=%.4g", f.parameter_names[k].c_str(), w.parameters[k]);
    }
    std::printf("\n");
    EXPECT_TRUE(w.converged) << name << ": " << w.status;
    EXPECT_LT(w.chi2, fl_log.wavelengths[0].chi2) << name;
    EXPECT_LT(w.bic, fl_log.wavelengths[0].bic) << name;
  }
}

INSTANTIATE_TEST_SUITE_P(Tapes, RetroTape, ::testing::Values("retro-3M-yellow.dat", "retro-gray-tape.dat"));

}  // namespace
}  // namespace roadbrdf
