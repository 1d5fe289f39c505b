// `convert` and `calibrate --manifest` on instrument files, through build/roadbrdf: the same
// results and errors as the library.
#include <gtest/gtest.h>

#include <fstream>

#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/instrument.h"
#include "roadbrdf/io/manifest.h"
#include "roadbrdf/spectra/spectrum_file.h"
#include "support/cli.h"
#include "support/paths.h"
#include "support/scratch.h"

namespace roadbrdf {
namespace {

std::string dir() { return test::instrument_files_dir() + "/"; }

TEST(InstrumentCli, CalibrateManifestEqualsTheLibrary) {
  const std::string out = test::scratch_path("run.brdf.csv");
  const auto r =
      test::run_cli("calibrate --manifest " + dir() + "run.csv --panel-reflectance " + dir() + "rho.txt -o " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  const SpectralDataset cli = read_dataset(out);
  const SpectralDataset lib =
      calibrate_manifest(read_manifest(dir() + "run.csv"), spectra::read_spectrum(dir() + "rho.txt"));
  EXPECT_EQ(cli.brdf, lib.brdf);
  EXPECT_EQ(cli.convention, AngleConvention::kRoad);
  EXPECT_EQ(cli.metadata.at("white_reference"), "run_white.asd");
  EXPECT_EQ(cli.metadata.at("asd.swir2_gain"), "616");
}

TEST(InstrumentCli, ConvertSingleFileAndManifest) {
  const std::string one = test::scratch_path("one.csv");
  auto r =
      test::run_cli("convert " + dir() + "sed_001.sed --geometry theta_i=0,phi_i=0,theta_r=30,phi_r=180 -o " + one);
  ASSERT_EQ(r.status, 0) << r.output;
  DatasetReadOptions any;
  any.any_units = true;
  const SpectralDataset d = read_dataset(one, any);
  EXPECT_EQ(d.metadata.at("units"), "normalized DN");
  EXPECT_EQ(d.brdf, read_instrument_file(dir() + "sed_001.sed").target);
  const std::string run = test::scratch_path("signals.csv");
  r = test::run_cli("convert " + dir() + "run_sed.csv --from manifest --quantity reference -o " + run);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(read_dataset(run, any).geometry_count(), 3u);
}

TEST(InstrumentCli, ErrorsNameTheProblem) {
  auto r = test::run_cli("convert " + dir() + "run_001.asd");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("an instrument file has no geometry: give --geometry"), std::string::npos) << r.output;
  r = test::run_cli("calibrate " + dir() + "run_001.asd --manifest " + dir() + "run.csv --panel-reflectance " + dir() +
                    "rho.txt");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--manifest gives the sample"), std::string::npos) << r.output;
  const std::string cut = test::scratch_path("cut.asd");
  {
    std::ifstream in(dir() + "run_001.asd", std::ios::binary);
    std::string bytes(700, '\0');
    in.read(bytes.data(), 700);
    std::ofstream(cut, std::ios::binary) << bytes;
  }
  r = test::run_cli("convert " + cut + " --geometry theta_i=0,phi_i=0,theta_r=30,phi_r=180");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find(cut + ": byte 697: file ends inside the reference spectrum"), std::string::npos) << r.output;
  r = test::run_cli("convert " + dir() + "sig_overlap.sig --overlap error --geometry gamma=0,alpha=45,beta=0,delta=0");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("sig_overlap.sig:30:1: detector overlap"), std::string::npos) << r.output;
  r = test::run_cli("convert " + dir() + "sig_overlap.sig --geometry gamma=0,alpha=45,beta=0,delta=0");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("roadbrdf: warning: " + dir() + "sig_overlap.sig: detector overlap"), std::string::npos);
}

}  // namespace
}  // namespace roadbrdf
