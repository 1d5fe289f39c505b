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

// A white-sky albedo of 1e-4 lies below the 0.005 no natural material reaches (docs/data.md): a
// warning of kind "implausibly_dark", printed once on standard error and listed in the JSON.
TEST(AlbedoCli, WarningsAreTypedAndPrintedOnce) {
  int status = 0;
  std::string out = run("albedo lambert -p albedo=1e-4 --quiet", status);
  ASSERT_EQ(status, 0) << out;
  const std::string line = "roadbrdf: warning: implausible: a white-sky albedo of 0.0001";
  ASSERT_NE(out.find(line), std::string::npos) << out;
  EXPECT_EQ(out.find(line, out.find(line) + 1), std::string::npos) << out;
  const std::string json_file = ::testing::TempDir() + "albedo_warnings.json";
  out = run("albedo lambert -p albedo=1e-4 --quiet --json -o " + json_file, status);
  ASSERT_EQ(status, 0) << out;
  FILE* f = std::fopen(json_file.c_str(), "r");
  ASSERT_NE(f, nullptr);
  const auto j = nlohmann::json::parse(f);
  std::fclose(f);
  ASSERT_EQ(j.at("warnings").size(), 1u) << j.at("warnings").dump();
  EXPECT_EQ(j.at("warnings")[0].at("kind"), "implausibly_dark");
  for (const auto& note : j.at("notes")) EXPECT_EQ(note.get<std::string>().find("WARNING"), std::string::npos);
}

// A Lambertian fit (300-2500 nm: most of the solar energy, so no warning) with u(albedo) = 0.01: its
// white-sky albedo is the albedo itself, so u = 0.01 too; --no-uncertainty (the request's
// `uncertainty` switched off) leaves it out and says so.
TEST(AlbedoCli, NoUncertaintyTurnsTheUncertaintiesOff) {
  const std::string fit = ::testing::TempDir() + "albedo_uncertainty.fit.json";
  FILE* f = std::fopen(fit.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fputs(R"({"format": "roadbrdf-fit", "version": 1, "best": "lambert", "fits": [{"model": "lambert",
    "options": {}, "wavelengths": [300, 2500], "parameters": {"albedo": [0.3, 0.3]}, "parameter_order": ["albedo"],
    "fixed": [], "stderr": {"albedo": [0.01, 0.01]}, "correlation": [[[1.0]], [[1.0]]]}]})",
             f);
  std::fclose(f);
  int status = 0;
  std::string out = run("albedo " + fit + " --json --quiet", status);
  ASSERT_EQ(status, 0) << out;
  auto j = nlohmann::json::parse(out);
  EXPECT_NEAR(j.at("uncertainty").at("white_sky")[0].get<double>(), 0.01, 1e-9);
  out = run("albedo " + fit + " --no-uncertainty --json --quiet", status);
  ASSERT_EQ(status, 0) << out;
  j = nlohmann::json::parse(out);
  EXPECT_TRUE(j.at("uncertainty").is_null());
  bool noted = false;
  for (const auto& note : j.at("notes"))
    noted = noted || note.get<std::string>().find("values only") != std::string::npos;
  EXPECT_TRUE(noted) << j.at("notes").dump();
}

}  // namespace
