// The roadbrdf program: models and eval sub-commands, error messages and exit codes.
#include <gtest/gtest.h>
#include "support/cli.h"
#include "support/scratch.h"

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "roadbrdf/core/math.h"
#include "support/paths.h"

namespace {

using Result = roadbrdf::test::CliResult;
Result run(const std::string& arguments) { return roadbrdf::test::run_cli(arguments); }

std::string temp_path(const std::string& name) { return roadbrdf::test::scratch_path("cli_test_" + name); }

TEST(CliEval, LambertAtOneGeometry) {
  const Result r = run("eval lambert -p albedo=0.5 --theta-i 30 --phi-i 0 --theta-r 45 --phi-r 180");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NEAR(std::stod(r.output), 0.5 / roadbrdf::kPi, 1e-10);
}

TEST(CliEval, UnknownModelIsAClearError) {
  const Result r = run("eval no-such-model --theta-i 0 --phi-i 0 --theta-r 0 --phi-r 0");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("unknown model 'no-such-model'"), std::string::npos) << r.output;
}

TEST(CliEval, UnknownAndOutOfBoundsParameters) {
  Result r = run("eval lambert -p rho=0.5 --theta-i 0 --phi-i 0 --theta-r 0 --phi-r 0");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("no parameter 'rho'"), std::string::npos) << r.output;
  r = run("eval lambert -p albedo=1.5 --theta-i 0 --phi-i 0 --theta-r 0 --phi-r 0");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("outside its bounds"), std::string::npos) << r.output;
}

TEST(CliEval, ZenithOutsideRange) {
  const Result r = run("eval lambert --theta-i 95 --phi-i 0 --theta-r 0 --phi-r 0");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("outside the zenith range"), std::string::npos) << r.output;
}

TEST(CliEval, GeometryFileInRoadConventionGetsABrdfColumn) {
  const std::string in = temp_path("road.csv");
  {
    std::ofstream f(in);
    f << "# sample: test\n"
         "gamma,alpha,beta,delta,label\n"
         "0,90,0,0,normal\n"
         "60,1,0,0,cie\n";
  }
  const std::string out = temp_path("road_out.csv");
  const Result r = run("eval oren-nayar -p albedo=0.4 -p sigma=0 --geometry " + in + " -o " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream f(out);
  std::stringstream text;
  text << f.rdbuf();
  const std::string s = text.str();
  EXPECT_NE(s.find("gamma,alpha,beta,delta,label,brdf"), std::string::npos) << s;
  EXPECT_NE(s.find("60,1,0,0,cie,0.1273239545"), std::string::npos) << s;  // 0.4 / pi
}

TEST(CliEval, MalformedGeometryFileNamesLineAndColumn) {
  const std::string in = temp_path("bad.csv");
  {
    std::ofstream f(in);
    f << "theta_i,phi_i,theta_r,phi_r\n"
         "10,0,20,0\n"
         "10,0,abc,0\n";
  }
  const Result r = run("eval lambert --geometry " + in);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find(in + ":3:6: 'abc' is not a number (angle in degrees)"), std::string::npos) << r.output;
}

TEST(CliModels, JsonListsPinnedParameterNames) {
  const Result r = run("models --json");
  ASSERT_EQ(r.status, 0);
  EXPECT_NE(r.output.find("\"name\": \"oren-nayar\""), std::string::npos);
  EXPECT_NE(r.output.find("\"name\": \"sigma\""), std::string::npos);
}

TEST(CliModels, MarkdownReferenceIsUpToDate) {
  // docs/models.md is generated from the metadata; regenerate it with
  //   build/roadbrdf models --markdown > docs/models.md
  const Result r = run("models --markdown");
  ASSERT_EQ(r.status, 0);
  std::ifstream f(roadbrdf::test::source_dir() + "/docs/models.md");
  std::stringstream text;
  text << f.rdbuf();
  EXPECT_EQ(text.str(), r.output) << "docs/models.md is stale: regenerate it";
}

}  // namespace
