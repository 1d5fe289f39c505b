// Fit files: written by write_fit_file / `roadbrdf fit`, read back by read_fit_file (models/spectral_model.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "roadbrdf/core/error.h"
#include "roadbrdf/fitting/fit.h"
#include "roadbrdf/fitting/fit_file.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/modelfile/fit_file_read.h"
#include "roadbrdf/models/registry.h"
#include "roadbrdf/models/spectral_model.h"
#include "support/paths.h"
#include "synthetic.h"

namespace roadbrdf {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  const fs::path dir = fs::temp_directory_path() / ("roadbrdf_fit_file_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

SpectralDataset on_data() {
  auto model = make_model("oren-nayar");
  std::vector<double> wl = {450.0, 500.0, 550.0, 600.0};
  return test::synthetic_dataset(
      *model, test::test_grid(), wl,
      [](std::size_t w) {
        return std::vector<double>{0.2 + 0.1 * double(w), 0.4};
      },
      0.01, 0.0, 21);
}

TEST(FitFile, WrittenFileReadsBackTheSameParameters) {
  const SpectralDataset data = on_data();
  auto on = make_model("oren-nayar");
  auto lambert = make_model("lambert");
  std::vector<FitResult> fits = {fit_model(*lambert, data, FitOptions{}), fit_model(*on, data, FitOptions{})};
  const fs::path path = temp_dir() / "fit.json";
  write_fit_file(path.string(), fits);
  {
    // The JSON itself (independently of read_fit_file): parameters per wavelength, exactly.
    std::ifstream in(path);
    const nlohmann::json j = nlohmann::json::parse(in);
    for (std::size_t i = 0; i < fits.size(); ++i) {
      const auto& f = j["fits"][i];
      EXPECT_EQ(f["model"], fits[i].model);
      for (std::size_t k = 0; k < fits[i].parameter_names.size(); ++k) {
        const auto values = f["parameters"][fits[i].parameter_names[k]].get<std::vector<double>>();
        ASSERT_EQ(values.size(), data.wavelengths.size());
        for (std::size_t w = 0; w < values.size(); ++w) EXPECT_EQ(values[w], fits[i].wavelengths[w].parameters[k]);
      }
    }
  }
  for (std::size_t i = 0; i < fits.size(); ++i) {
    const SpectralModel sm = read_fit_file(path.string(), fits[i].model);
    ASSERT_EQ(sm.wavelengths().size(), data.wavelengths.size());
    const std::size_t p = fits[i].parameter_names.size();
    for (std::size_t w = 0; w < data.wavelengths.size(); ++w) {
      EXPECT_EQ(sm.wavelengths()[w], data.wavelengths[w]);
      for (std::size_t k = 0; k < p; ++k)
        EXPECT_EQ(sm.parameter_table()[w * p + k], fits[i].wavelengths[w].parameters[k]);
    }
  }
  // Several fits from one parse of the file: the parameters written, in the order asked ("" the best).
  const std::vector<SpectralModel> models = read_fit_file_models(path.string(), {"lambert", "oren-nayar", ""});
  ASSERT_EQ(models.size(), 3u);
  for (std::size_t i = 0; i < models.size(); ++i) {
    const FitResult& f = fits[std::min<std::size_t>(i, 1)];
    EXPECT_EQ(models[i].model().name(), f.model);
    const std::size_t p = f.parameter_names.size();
    ASSERT_EQ(models[i].parameter_table().size(), data.wavelengths.size() * p);
    for (std::size_t w = 0; w < data.wavelengths.size(); ++w) {
      for (std::size_t k = 0; k < p; ++k)
        EXPECT_EQ(models[i].parameter_table()[w * p + k], f.wavelengths[w].parameters[k]);
    }
  }
  EXPECT_THROW(read_fit_file_models(path.string(), {"lambert", "hapke"}), FileError);
  // Oren-Nayar data: the best (lowest BIC) is oren-nayar, and "best" names it.
  EXPECT_EQ(read_fit_file(path.string()).model().name(), "oren-nayar");
  std::ifstream in(path);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["format"], "roadbrdf-fit");
  EXPECT_EQ(j["best"], "oren-nayar");
  const auto& f = j["fits"][1];
  for (const char* key :
       {"stderr", "rmse", "rmse_total", "relative_rmse", "max_relative_error", "r_squared", "aic", "bic", "iterations",
        "converged", "status", "at_bounds", "correlation", "covariance_ok", "aic_total", "bic_total"}) {
    EXPECT_TRUE(f.contains(key)) << key;
  }
  EXPECT_EQ(f["stderr"]["sigma"].size(), 4u);
  EXPECT_NEAR(f["correlation"][0][0][0].get<double>(), 1.0, 1e-12);
  fs::remove_all(path.parent_path());
}

int run(const std::string& command) { return std::system((command + " > /dev/null 2> /dev/null").c_str()); }

TEST(FitFile, CommandLineFitRanksAndWritesFiles) {
  const fs::path dir = temp_dir();
  const fs::path data_path = dir / "data.csv", fit_path = dir / "fit.json", res_path = dir / "res.csv";
  const SpectralDataset data = on_data();
  write_dataset(data, data_path.string());
  const std::string cli = roadbrdf::test::cli_program();
  ASSERT_EQ(run(cli + " fit " + data_path.string() + " --model lambert --model oren-nayar --threads 2 --residuals " +
                res_path.string() + " -o " + fit_path.string()),
            0);
  const SpectralModel best = read_fit_file(fit_path.string());
  EXPECT_EQ(best.model().name(), "oren-nayar");
  EXPECT_NEAR(best.parameters_at(500.0)[1], 0.4, 0.05);
  // Residual file: header + one row per geometry, wavelength and model.
  std::ifstream res(res_path);
  std::size_t rows = 0;
  std::string line;
  while (std::getline(res, line)) {
    if (!line.empty() && line[0] != '#') ++rows;
  }
  EXPECT_EQ(rows, 1 + 2 * data.geometry_count() * data.wavelength_count());
  // Joint mode, a wavelength subset and a fixed parameter.
  ASSERT_EQ(run(cli + " fit " + data_path.string() + " --model oren-nayar --shared sigma --wavelengths 450:550:50 -o " +
                fit_path.string()),
            0);
  const SpectralModel joint = read_fit_file(fit_path.string());
  ASSERT_EQ(joint.wavelengths().size(), 3u);
  EXPECT_EQ(joint.parameter_table()[1], joint.parameter_table()[3]);
  // Errors: unknown parameter, bad loss, missing file (exit code 2 = input error).
  EXPECT_NE(run(cli + " fit " + data_path.string() + " --model oren-nayar --fix roughness=1 -o " + fit_path.string()),
            0);
  EXPECT_NE(run(cli + " fit " + data_path.string() + " --model oren-nayar --loss l1 -o " + fit_path.string()), 0);
  EXPECT_NE(run(cli + " fit " + (dir / "missing.csv").string() + " --model lambert -o " + fit_path.string()), 0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace roadbrdf
