// `roadbrdf marking` with a pavement, through the program: the contrast in --json and in the text
// summary (a Lambertian marking of albedo 0.6 on a Lambertian pavement of albedo 0.1: C = 0.6 / 0.1 - 1
// = 5 under any light), and a missing pavement file refused with the option and the file named.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/cli.h"

namespace roadbrdf::test {
namespace {

const std::string kLambertian = "marking lambert -p albedo=0.6 --pavement lambert --pavement-parameter albedo=0.1";

TEST(CliMarkingContrast, JsonAndTextCarryTheContrast) {
  const std::string lamp = test_data_dir() + "/lighting/headlamp.ies";
  const std::string installation = test_data_dir() + "/lighting/installation.json";
  const CliResult json = run_shell(cli_program() + " " + kLambertian + " --headlamp " + lamp + " --installation " +
                                   installation + " --json");
  ASSERT_EQ(json.status, 0) << json.output;
  const nlohmann::json j = nlohmann::json::parse(json.output);
  EXPECT_NEAR(j["contrast"]["headlamp"]["contrast"].get<double>(), 5.0, 1e-12);
  EXPECT_GT(j["contrast"]["headlamp"]["light"]["illuminance_lx"].get<double>(), 0.0);
  EXPECT_NEAR(j["contrast"]["installation"]["contrast_of_averages"].get<double>(), 5.0, 1e-8);
  EXPECT_EQ(j["contrast"]["installation"]["observers"].size(), 2u);

  const CliResult text = run_cli(kLambertian);
  ASSERT_EQ(text.status, 0) << text.output;
  EXPECT_NE(text.output.find("contrast against lambert"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("C = 5"), std::string::npos) << text.output;
}

TEST(CliMarkingContrast, MissingPavementFileIsRefusedByName) {
  const CliResult r = run_cli("marking lambert --pavement no-such-pavement.fit.json");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--pavement"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("no-such-pavement.fit.json"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace roadbrdf::test
