// Formulation files: parsing, validation errors naming the file and the key, example F1-F4.
#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "roadbrdf/core/data_path.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/formulation/formulation.h"

namespace {

using namespace roadbrdf;
namespace fs = std::filesystem;

class FormulationFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("roadbrdf_formulation_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_ / "fits");
    for (const char* name : {"bitumen", "sand", "gravel", "mastic"}) {
      std::ofstream(dir_ / "fits" / (std::string(name) + ".fit.json")) << "{}\n";
    }
    fs::create_directories(dir_ / "formulations");
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& text) {
    const fs::path p = dir_ / "formulations" / "test.json";
    std::ofstream(p) << text;
    return p.string();
  }

  static std::string document(const std::string& bitumen_extra = "", double sand_percent = 40.0,
                              const std::string& gravel_fit = "../fits/gravel.fit.json", double gravel_density = 2.7) {
    std::ostringstream s;
    s << R"({ "format": "roadbrdf-formulation", "version": 1, "name": "T",
      "mastic": { "name": "m", "fit": "../fits/mastic.fit.json" },
      "components": [
        { "name": "Bitumen", "kind": "binder", "mass_percent": 5, "density_g_cm3": 1.03,
          "fit": "../fits/bitumen.fit.json" )"
      << bitumen_extra << R"( },
        { "name": "Sand 0/2", "kind": "aggregate", "mass_percent": )"
      << sand_percent << R"(, "density_g_cm3": 2.65, "d_min_mm": 0, "d_max_mm": 2,
          "fit": "../fits/sand.fit.json" },
        { "name": "Gravel 6/10", "kind": "aggregate", "mass_percent": 55, "density_g_cm3": )"
      << gravel_density << R"(, "d_min_mm": 6, "d_max_mm": 10, "fit": ")" << gravel_fit << R"(" } ] })";
    return s.str();
  }

  // The FileError message of reading `text`, or "" if it parsed.
  std::string error_of(const std::string& text) {
    try {
      read_formulation(write(text));
    } catch (const FileError& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
};

TEST_F(FormulationFiles, ParsesAndResolvesFitPaths) {
  const Formulation f = read_formulation(write(document()));
  EXPECT_EQ(f.name, "T");
  ASSERT_EQ(f.components.size(), 3u);
  EXPECT_EQ(f.components[0].kind, ComponentKind::kBinder);
  EXPECT_DOUBLE_EQ(f.components[1].mass_percent, 40.0);
  EXPECT_TRUE(fs::equivalent(f.components[2].fit_path, dir_ / "fits" / "gravel.fit.json"));
  ASSERT_TRUE(f.mastic.has_value());
  EXPECT_TRUE(fs::equivalent(f.mastic->fit_path, dir_ / "fits" / "mastic.fit.json"));
  EXPECT_FALSE(is_coarse(f, f.components[1]));
  EXPECT_TRUE(is_coarse(f, f.components[2]));
  // Effective diameters: logarithmic mean, d_min = 0 -> 0.063 mm; binder -> film thickness.
  EXPECT_NEAR(effective_diameter_mm(f, f.components[1]), (2.0 - 0.063) / std::log(2.0 / 0.063), 1e-12);
  EXPECT_NEAR(effective_diameter_mm(f, f.components[2]), 4.0 / std::log(10.0 / 6.0), 1e-12);
  EXPECT_DOUBLE_EQ(effective_diameter_mm(f, f.components[0]), 0.01);
}

TEST_F(FormulationFiles, FractionsMustSumTo100) {
  const std::string e = error_of(document("", 41.0));  // 101 %
  EXPECT_NE(e.find("test.json"), std::string::npos) << e;
  EXPECT_NE(e.find("mass_percent"), std::string::npos) << e;
  EXPECT_NE(e.find("101"), std::string::npos) << e;
  // Within the default tolerance of 0.5 %.
  EXPECT_EQ(error_of(document("", 40.3)), "");
}

TEST_F(FormulationFiles, UnknownFitFileIsAnError) {
  const std::string e = error_of(document("", 40.0, "../fits/nonexistent.fit.json"));
  EXPECT_NE(e.find("test.json"), std::string::npos) << e;
  EXPECT_NE(e.find("components[2] (\"Gravel 6/10\").fit"), std::string::npos) << e;
  EXPECT_NE(e.find("nonexistent.fit.json"), std::string::npos) << e;
}

TEST_F(FormulationFiles, NegativeDensityIsAnError) {
  const std::string e = error_of(document("", 40.0, "../fits/gravel.fit.json", -2.7));
  EXPECT_NE(e.find("components[2] (\"Gravel 6/10\").density_g_cm3"), std::string::npos) << e;
  EXPECT_NE(e.find("> 0"), std::string::npos) << e;
}

TEST_F(FormulationFiles, OtherInconsistencies) {
  EXPECT_NE(error_of(document(R"(, "colour": "black")")).find("components[0] (\"Bitumen\").colour"), std::string::npos);
  EXPECT_NE(error_of(document(R"(, "d_min_mm": 1)")).find("go together"), std::string::npos);
  EXPECT_NE(error_of(R"({"format": "roadbrdf-formulation", "version": 1, "name": "x", "components": []})")
                .find("at least one component"),
            std::string::npos);
  EXPECT_NE(
      error_of(R"({"format": "roadbrdf-formulation", "version": 2, "name": "x", "components": []})").find("version"),
      std::string::npos);
  EXPECT_NE(error_of("{ not json").find("not valid JSON"), std::string::npos);
  std::string doc = document();
  doc.replace(doc.find("\"binder\""), 8, "\"glue\"");
  EXPECT_NE(error_of(doc).find(".kind"), std::string::npos);
  doc = document();
  doc.replace(doc.find("\"d_min_mm\": 6"), 13, "\"d_min_mm\": 12");
  EXPECT_NE(error_of(doc).find("exceeds d_max_mm"), std::string::npos);
  doc = document();
  doc.replace(doc.find("\"Sand 0/2\""), 10, "\"Bitumen\"");
  EXPECT_NE(error_of(doc).find("duplicate"), std::string::npos);
  doc = document();
  doc.replace(doc.find("\"d_min_mm\": 0, \"d_max_mm\": 2,"), 29, "");
  EXPECT_NE(error_of(doc).find("size class"), std::string::npos);
}

// The bundled examples follow Table 5.1 (values typed here from the report).
TEST(ExampleFormulations, MatchTable51) {
  struct Expected {
    const char* name;
    std::vector<std::pair<const char*, double>> components;
  };
  const std::vector<Expected> table = {
      {"F1",
       {{"Limestone filler", 1.4},
        {"Bitumen", 5.2},
        {"Garonne 0/2", 31.1},
        {"Garonne 2/6", 19.2},
        {"Garonne 6/10", 43.1}}},
      {"F2",
       {{"Limestone filler", 2.2},
        {"Bitumen", 5.3},
        {"Soreze limestone 0/2", 28.3},
        {"Lazard 2/6", 19.5},
        {"Lazard 6/10", 44.7}}},
      {"F3",
       {{"Limestone filler", 1.4},
        {"TiO2", 0.5},
        {"Synthetic binder", 5.4},
        {"Soreze limestone 0/2", 27.5},
        {"Lazard 2/6", 21.0},
        {"Lazard 6/10", 44.2}}},
      {"F4",
       {{"Limestone filler", 1.9},
        {"Bitumen", 5.4},
        {"Garonne 0/2", 29.5},
        {"Garonne 2/6", 19.8},
        {"Gouraudiere 6/10", 43.4}}},
  };
  for (const Expected& e : table) {
    const std::string path = data_directory() + "/examples/formulations/" + e.name + ".json";
    std::ifstream in(path);
    ASSERT_TRUE(in) << path;
    std::stringstream text;
    text << in.rdbuf();
    const Formulation f = parse_formulation(text.str(), path, /*check_files=*/false);
    EXPECT_EQ(f.name, e.name);
    ASSERT_EQ(f.components.size(), e.components.size()) << e.name;
    for (std::size_t i = 0; i < e.components.size(); ++i) {
      EXPECT_EQ(f.components[i].name, e.components[i].first);
      EXPECT_DOUBLE_EQ(f.components[i].mass_percent, e.components[i].second);
    }
    ASSERT_TRUE(f.mastic.has_value());
  }
}

}  // namespace
