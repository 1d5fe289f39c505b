// `roadbrdf convert --from usgs` through build/roadbrdf: the library's dataset (io/usgs.h) and the
// command line's errors, on small synthetic splib07a files written here.
#include <gtest/gtest.h>

#include <fstream>
#include <numbers>

#include "roadbrdf/io/dataset_io.h"
#include "support/cli.h"
#include "support/scratch.h"

namespace roadbrdf {
namespace {

struct Files {
  std::string spectrum, wavelengths;
};

// Three channels at 400, 500, 600 nm; the second is deleted (-1.23e+34, the library's marker).
Files files() {
  const Files f{test::scratch_path("usgs_s.txt"), test::scratch_path("usgs_w.txt")};
  std::ofstream(f.spectrum)
      << " splib07a Record=5: synthetic ASDFRa AREF\n 2.5000000e-001\n-1.2300000e+034\n 5.0000000e-001\n";
  std::ofstream(f.wavelengths)
      << " splib07a Record=6: Wavelengths synthetic\n 4.0000001e-001\n 5.0000000e-001\n 5.9999999e-001\n";
  return f;
}

TEST(UsgsCli, ConvertStoresReflectanceOverPiAtTheGivenGeometry) {
  const Files f = files();
  const std::string out = test::scratch_path("usgs.csv");
  const auto r = test::run_cli("convert " + f.spectrum + " --from usgs --usgs-wavelengths " + f.wavelengths +
                               " --geometry gamma=30,alpha=1,beta=0,delta=0 -o " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("usgs_s.txt: 1 missing channels (-1.23e+34) left out"), std::string::npos) << r.output;
  const SpectralDataset d = read_dataset(out);
  ASSERT_EQ(d.wavelengths, (std::vector<double>{400.0, 600.0}));
  ASSERT_EQ(d.brdf.size(), 2u);
  EXPECT_NEAR(d.brdf[0], 0.25 / std::numbers::pi, 1e-15);
  EXPECT_NEAR(d.brdf[1], 0.5 / std::numbers::pi, 1e-15);
  EXPECT_EQ(d.convention, AngleConvention::kRoad);
  EXPECT_EQ(d.metadata.at("usgs.record"), "5");
  EXPECT_EQ(d.metadata.at("usgs.missing_channels"), "1");
}

TEST(UsgsCli, ErrorsNameTheProblem) {
  const Files f = files();
  auto r = test::run_cli("convert " + f.spectrum + " --from usgs --geometry theta_i=30,phi_i=0,theta_r=0,phi_r=0");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--from usgs needs --usgs-wavelengths FILE"), std::string::npos) << r.output;
  r = test::run_cli("convert " + f.spectrum + " --from usgs --usgs-wavelengths " + f.wavelengths);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("an instrument file has no geometry: give --geometry"), std::string::npos) << r.output;
  r = test::run_cli("convert " + f.spectrum + " --from usgs --usgs-wavelengths " + f.wavelengths +
                    " --quantity reference --geometry theta_i=30,phi_i=0,theta_r=0,phi_r=0");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("holds no reference signal"), std::string::npos) << r.output;
  r = test::run_cli("convert " + f.spectrum + " --from sed --usgs-wavelengths " + f.wavelengths +
                    " --geometry theta_i=30,phi_i=0,theta_r=0,phi_r=0");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--usgs-wavelengths is for --from usgs"), std::string::npos) << r.output;
  // The wrong wavelength file (two channels for a three-channel spectrum): named at the spectrum's extra value.
  const std::string two = test::scratch_path("usgs_w2.txt");
  std::ofstream(two) << " splib07a Record=7: Wavelengths other\n 0.4\n 0.5\n";
  r = test::run_cli("convert " + f.spectrum + " --from usgs --usgs-wavelengths " + two +
                    " --geometry theta_i=30,phi_i=0,theta_r=0,phi_r=0");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("usgs_s.txt:4:1: 3 values but the wavelength file has 2"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace roadbrdf
