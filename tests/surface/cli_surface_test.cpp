// The roadbrdf program: surface and render sub-commands.
#include <gtest/gtest.h>
#include "support/cli.h"
#include "support/scratch.h"

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

std::string temp_path(const std::string& name) { return roadbrdf::test::scratch_path("cli_surface_" + name); }

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
  r = run("render " + surface + " --grid " + grid + " --wavelengths 400:600:100 --samples 64 --acceptance 5 -o " +
          data);
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
  const Result r =
      run("surface " + folder + "/mix.json --size 12mm --cell 0.1 --seed 4 --preview " + png + " -o " + surface);
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

// `render --albedo`: a flat Lambertian sample has black-sky and white-sky albedo equal to its albedo
// exactly (every path weighs pi * albedo/pi; the Gauss-Legendre weights 2 w_k mu_k sum to 1).
TEST(CliSurface, RenderAlbedoOfAFlatLambertianSample) {
  const std::string surface = temp_path("alb_flat.json"), out = temp_path("alb.csv");
  ASSERT_EQ(run("surface lambert --flat -p albedo=0.35 -o " + surface).status, 0);
  Result r = run("render " + surface + " --albedo 0,45 --wavelengths 500:600:100 --samples 64 -o " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(out);
  std::string line, header;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("# virtual albedo of", 0), 0u) << line;
  std::getline(in, header);
  EXPECT_EQ(header,
            "wavelength_nm,white_sky,white_sky_error,black_sky_0deg,black_sky_error_0deg,black_sky_45deg,"
            "black_sky_error_45deg");
  int rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    double w, white, white_e, b0, b0_e, b45, b45_e;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf,%lf", &w, &white, &white_e, &b0, &b0_e, &b45, &b45_e),
              7)
        << line;
    EXPECT_NEAR(white, 0.35, 1e-7);
    EXPECT_NEAR(b0, 0.35, 1e-7);
    EXPECT_NEAR(b45, 0.35, 1e-7);
    EXPECT_EQ(b45_e, 0.0);
  }
  EXPECT_EQ(rows, 2);
  // Exactly one of --grid and --albedo; --albedo angles must be below 90 deg.
  EXPECT_EQ(run("render " + surface + " --samples 8 -o " + out).status, 2);
  EXPECT_EQ(run("render " + surface + " --albedo 90 --samples 8 -o " + out).status, 2);
  for (const auto& p : {surface, out}) std::filesystem::remove(p);
}

// `render --target-error`: every geometry of a rough sample reaches the target (recorded in the
// dataset's metadata); --samples and --target-error exclude each other.
TEST(CliSurface, RenderToATargetError) {
  const std::string surface = temp_path("rough.json"), grid = temp_path("rough_grid.csv"),
                    data = temp_path("rough.csv");
  ASSERT_EQ(run("surface oren-nayar -p albedo=0.5 -p sigma=0.3 --gaussian-slopes 0.4 --cells 64 -o " + surface).status,
            0);
  write_text(grid, "theta_i,phi_i,theta_r,phi_r\n0,0,30,0\n60,0,60,180\n");
  Result r = run("render " + surface + " --grid " + grid + " --target-error 0.02 --acceptance 5 -o " + data);
  ASSERT_EQ(r.status, 0) << r.output;
  const roadbrdf::SpectralDataset d = roadbrdf::read_dataset(data);
  for (std::size_t k = 0; k < d.brdf.size(); ++k) EXPECT_LE(d.sigma[k], 0.02 * d.brdf[k] + 1e-12) << k;
  EXPECT_EQ(d.metadata.at("geometries_not_converged"), "none");
  EXPECT_EQ(run("render " + surface + " --grid " + grid + " --samples 64 --target-error 0.02 -o " + data).status, 2);
  for (const auto& p : {surface, grid, data}) std::filesystem::remove(p);
}

// The material is built by the library (surface/materials.h material_spec), which names its fields.
TEST(CliSurface, MaterialErrorsNameTheFlag) {
  const std::string fit = temp_path("mat_err.fit.json"), surface = temp_path("mat_err.json");
  write_text(fit, "{}");
  Result r = run("surface " + fit + " --flat -p albedo=0.5 -o " + surface);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--parameter: apply to a model, not to a fit file"), std::string::npos) << r.output;
  r = run("surface lambert --flat --fit lambert -o " + surface);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--fit: selects a fit of a fit file; 'lambert' is a model name"), std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(surface));
  std::filesystem::remove(fit);
}

// --size is read as every number is (core/number.h): a hexadecimal length is refused.
TEST(CliSurface, SizeIsReadAsEveryNumber) {
  const std::string surface = temp_path("size_err.json");
  const Result r = run("surface missing.formulation.json --size 0x3cmm -o " + surface);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--size: expected a length such as 60mm, got '0x3cmm'"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(surface));
}
