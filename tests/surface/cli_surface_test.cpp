// The roadbrdf program: surface and render sub-commands.
#include "support/cli.h"
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "roadbrdf/core/math.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/surface/height_field.h"

namespace {

using Result = roadbrdf::test::CliResult;
Result run(const std::string& arguments) { return roadbrdf::test::run_cli(arguments); }

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("roadbrdf_cli_surface_" + name)).string();
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

}  // namespace

TEST(CliSurface, FlatLambertRendersItsAlbedoOverPi) {
  const std::string surface = temp_path("flat.json"), grid = temp_path("grid.csv"), data = temp_path("flat.csv");
  Result r = run("surface lambert --flat -p albedo=0.5 -o " + surface);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("MPD 0.000 mm"), std::string::npos) << r.output;
  write_text(grid, "theta_i,phi_i,theta_r,phi_r\n0,0,30,0\n60,0,60,180\n45,10,20,100\n");
  r = run("render " + surface + " --grid " + grid + " --wavelengths 400:600:100 --samples 64 --acceptance 5 -o " + data);
  ASSERT_EQ(r.status, 0) << r.output;
  const roadbrdf::SpectralDataset d = roadbrdf::read_dataset(data);
  ASSERT_EQ(d.geometry_count(), 3u);
  ASSERT_EQ(d.wavelength_count(), 3u);
  ASSERT_TRUE(d.has_sigma());
  for (std::size_t k = 0; k < d.brdf.size(); ++k) {
    EXPECT_NEAR(d.brdf[k], 0.5 / roadbrdf::kPi, 1e-12);
    EXPECT_EQ(d.sigma[k], 0.0);
  }
  EXPECT_EQ(d.metadata.at("acceptance_half_angle_deg"), "5");
  for (const auto& p : {surface, grid, data}) std::filesystem::remove(p);
}

TEST(CliSurface, FormulationSampleWithPreview) {
  const std::string folder = temp_path("formulation");
  std::filesystem::create_directories(folder);
  write_text(folder + "/mix.json", R"({
    "format": "roadbrdf-formulation", "version": 1, "name": "M",
    "mastic": {"name": "mastic", "fit": "mastic.fit.json"},
    "components": [
      {"name": "Bitumen", "kind": "binder", "mass_percent": 6, "density_g_cm3": 1.03, "fit": "mastic.fit.json"},
      {"name": "Sand 0/2", "kind": "aggregate", "mass_percent": 34, "density_g_cm3": 2.65, "d_min_mm": 0,
       "d_max_mm": 2, "fit": "mastic.fit.json"},
      {"name": "Gravel 2/4", "kind": "aggregate", "mass_percent": 60, "density_g_cm3": 2.65, "d_min_mm": 2,
       "d_max_mm": 4, "fit": "gravel.fit.json"}
    ]})");
  const std::string surface = folder + "/sample.json", png = folder + "/sample.png";
  const Result r = run("surface " + folder + "/mix.json --size 12mm --cell 0.1 --seed 4 --preview " + png + " -o " + surface);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("Gravel 2/4"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("does not exist yet"), std::string::npos) << r.output;  // fits are needed only to render
  const roadbrdf::surface::HeightField f = roadbrdf::surface::read_surface(surface);
  EXPECT_EQ(f.nx, 120);
  ASSERT_EQ(f.materials.size(), 2u);
  EXPECT_EQ(f.materials[0].name, "mastic");
  EXPECT_EQ(f.materials[1].name, "Gravel 2/4");
  EXPECT_EQ(f.materials[1].fit, "gravel.fit.json");  // relative to the SURFACE file's folder
  EXPECT_TRUE(std::filesystem::exists(png));
  std::filesystem::remove_all(folder);
}

// A material given as a fit file: parameters interpolated at each wavelength; default wavelengths
// are the fit's.
TEST(CliSurface, FitFileMaterialIsSpectral) {
  const std::string fit = temp_path("lam.fit.json"), surface = temp_path("fitflat.json"),
                    grid = temp_path("fitgrid.csv"), data = temp_path("fit.csv");
  write_text(fit, R"({"format": "roadbrdf-fit", "version": 1, "best": "lambert",
    "fits": [{"model": "lambert", "options": {}, "wavelengths": [400, 700], "parameters": {"albedo": [0.2, 0.6]}}]})");
  write_text(grid, "theta_i,phi_i,theta_r,phi_r\n20,0,40,180\n");
  Result r = run("surface " + fit + " --flat -o " + surface);
  ASSERT_EQ(r.status, 0) << r.output;
  r = run("render " + surface + " --grid " + grid + " --samples 8 -o " + data);
  ASSERT_EQ(r.status, 0) << r.output;
  roadbrdf::SpectralDataset d = roadbrdf::read_dataset(data);
  ASSERT_EQ(d.wavelengths, (std::vector<double>{400.0, 700.0}));
  EXPECT_NEAR(d.value(0, 0), 0.2 / roadbrdf::kPi, 1e-12);
  EXPECT_NEAR(d.value(0, 1), 0.6 / roadbrdf::kPi, 1e-12);
  r = run("render " + surface + " --grid " + grid + " --samples 8 --wavelengths 550 -o " + data);
  ASSERT_EQ(r.status, 0) << r.output;
  d = roadbrdf::read_dataset(data);
  EXPECT_NEAR(d.value(0, 0), 0.4 / roadbrdf::kPi, 1e-12);
  for (const auto& p : {fit, surface, grid, data}) std::filesystem::remove(p);
}

TEST(CliSurface, ErrorsAreClear) {
  const std::string surface = temp_path("err.json");
  Result r = run("surface lambert --flat -p rho=0.5 -o " + surface);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("rho"), std::string::npos) << r.output;
  r = run("surface lambert --flat -o " + surface);
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string grid = temp_path("err_grid.csv");
  write_text(grid, "theta_i,phi_i,theta_r,phi_r\n90,0,30,0\n");
  r = run("render " + surface + " --grid " + grid + " -o " + temp_path("err.csv"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("theta_i = 90"), std::string::npos) << r.output;
  std::filesystem::remove(surface);
  std::filesystem::remove(grid);
}
