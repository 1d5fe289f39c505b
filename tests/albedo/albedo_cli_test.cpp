// roadbrdf albedo: JSON keys and a closed-form value (Lambert: every albedo equals the parameter).
#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include "support/paths.h"

namespace {

std::string run(const std::string& args, int& status) {
  std::string out;
  FILE* pipe = popen((roadbrdf::test::cli_program() + " " + args + " 2>&1").c_str(), "r");
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) out += buffer;
  status = pclose(pipe);
  return out;
}

TEST(AlbedoCli, JsonKeysAndLambertValues) {
  int status = 0;
  const std::string out =
      run("albedo lambert -p albedo=0.42 --sun-zenith 0:60:30 --atmosphere spectrl2:aod=0.2 --json", status);
  ASSERT_EQ(status, 0) << out;
  const auto j = nlohmann::json::parse(out);
  for (const char* key : {"wavelengths", "black_sky", "white_sky", "blue_sky", "diffuse_fraction", "broadband",
                          "black_sky_error", "white_sky_error", "units"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  ASSERT_EQ(j["black_sky"].size(), 3u);
  EXPECT_NEAR(j["black_sky"][1][0].get<double>(), 0.42, 1e-12);
  EXPECT_NEAR(j["white_sky"][0].get<double>(), 0.42, 1e-12);
  EXPECT_NEAR(j["broadband"]["blue_sky"][2].get<double>(), 0.42, 1e-12);
  const double d = j["diffuse_fraction"][0][0].get<double>();
  EXPECT_GT(d, 0.0);
  EXPECT_LT(d, 1.0);
}

TEST(AlbedoCli, RejectsBadInput) {
  // The library's request validation names fields (AlbedoRequest::validate); the command line
  // names its flags for them.
  int status = 0;
  std::string out = run("albedo lambert -p albedo=0.3 --sun-zenith 95", status);
  EXPECT_NE(status, 0);
  EXPECT_NE(out.find("roadbrdf: error: --sun-zenith: must be in [0, 90) deg, got 95"), std::string::npos) << out;
  out = run("albedo lambert -p albedo=0.3 --diffuse-fraction 0.2 --atmosphere spectrl2", status);
  EXPECT_NE(status, 0);
  EXPECT_NE(out.find("--diffuse-fraction: excludes atmosphere"), std::string::npos) << out;
  out = run("albedo lambert -p albedo=0.3 --diffuse-fraction 1.5", status);
  EXPECT_NE(status, 0);
  EXPECT_NE(out.find("--diffuse-fraction: must be in [0, 1]"), std::string::npos) << out;
  out = run("albedo lambert -p albedo=0.3 --tolerance 0", status);
  EXPECT_NE(status, 0);
  EXPECT_NE(out.find("--tolerance: must be > 0"), std::string::npos) << out;
  out = run("albedo lambert -p albedo=0.3 --wavelengths 500", status);
  EXPECT_NE(status, 0);
  EXPECT_NE(out.find("--wavelengths: needs a fit file"), std::string::npos) << out;
  run("albedo lambert --atmosphere spectrl2:bogus=1", status);
  EXPECT_NE(status, 0);
}

}  // namespace
