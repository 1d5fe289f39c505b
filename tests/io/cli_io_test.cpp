// End-to-end runs of the measurement sub-commands through build/roadbrdf.
#include <gtest/gtest.h>
#include "support/cli.h"
#include "support/scratch.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "roadbrdf/core/data_path.h"
#include "roadbrdf/io/dataset_io.h"
#include "support/paths.h"

namespace roadbrdf {
namespace {

const std::string kCli = roadbrdf::test::cli_program();
const std::string kData = roadbrdf::data_directory();

using Result = roadbrdf::test::CliResult;
Result run(const std::string& arguments) { return roadbrdf::test::run_cli(arguments); }

std::string tmp(const std::string& name) { return roadbrdf::test::scratch_path("cli_io_" + name); }

TEST(CliIo, SimulateCheckResampleConvert) {
  const std::string grid = tmp("grid.csv");
  std::ofstream(grid) << "theta_i,phi_i,theta_r,phi_r\n0,0,30,180\n30,0,0,0\n30,0,30,180\n30,0,60,90\n60,0,30,90\n";
  const std::string data = tmp("lambert.csv");
  Result r = run("simulate lambert -p albedo=0.5 --grid " + grid +
                 " --wavelengths 400:700:10 --noise relative=0.01 --seed 4 -o " + data);
  ASSERT_EQ(r.status, 0) << r.output;
  const SpectralDataset d = read_dataset(data);
  EXPECT_EQ(d.geometry_count(), 5u);
  EXPECT_EQ(d.wavelength_count(), 31u);
  EXPECT_TRUE(d.has_sigma());
  EXPECT_EQ(d.metadata.at("seed"), "4");

  r = run("check " + data + " --json");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto j = nlohmann::json::parse(r.output);
  EXPECT_EQ(j["geometries"], 5);
  EXPECT_EQ(j["reciprocity"]["pairs"], 2);  // (0,30)<->(30,0) and (30,60,|dphi| 90)<->(60,30)
  EXPECT_EQ(j["negative_values"], 0);

  const std::string resampled = tmp("resampled.csv");
  r = run("resample " + data + " --wavelengths 400:700:100 -o " + resampled);
  ASSERT_EQ(r.status, 0) << r.output;
  const SpectralDataset rs = read_dataset(resampled);
  EXPECT_EQ(rs.wavelengths, (std::vector<double>{450, 550, 650}));
  // Band average = trapezoid mean of the 11 samples of each band (independent computation).
  for (std::size_t g = 0; g < 5; ++g) {
    double sum = 0.0;
    for (std::size_t k = 0; k <= 10; ++k) sum += (k == 0 || k == 10 ? 0.5 : 1.0) * d.value(g, k);
    EXPECT_NEAR(rs.value(g, 0), sum / 10.0, 1e-15);
  }

  const std::string long_file = tmp("long.csv");
  r = run("convert " + data + " --to long --convention road -o " + long_file);
  ASSERT_EQ(r.status, 0) << r.output;
  const SpectralDataset back = read_dataset(long_file);
  EXPECT_EQ(back.convention, AngleConvention::kRoad);
  EXPECT_EQ(back.brdf, d.brdf);

  const std::string curet = tmp("curet.csv");
  r = run("convert " + kData + "/third-party/curet/abrdf.dat --from curet --sample 45 -o " + curet);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(read_dataset(curet).geometry_count(), 205u);
}

TEST(CliIo, ErrorsNameFileLineColumn) {
  const std::string bad = tmp("bad.csv");
  std::ofstream(bad) << "theta_i,phi_i,theta_r,phi_r,500\n0,0,30,180,oops\n";
  const Result r = run("check " + bad);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find(bad + ":2:12: 'oops'"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace roadbrdf
