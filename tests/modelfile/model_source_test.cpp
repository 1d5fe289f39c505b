// The one resolver of a model argument (modelfile/model_source.h): a model name with parameters, a
// fit file and a MIX.json, each written here by hand, give the BRDF of a Lambertian reflector
// f = rho / pi (report eq. 2.12) with the albedo the file or the assignment holds; a mixture of two
// Lambertian end-members is the area-weighted sum of theirs. Misplaced fields are refused by name.
#include <gtest/gtest.h>

#include <fstream>
#include <numbers>
#include <string>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/modelfile/model_source.h"
#include "support/scratch.h"

namespace roadbrdf {
namespace {

std::string write(const std::string& name, const std::string& text) {
  const std::string path = test::scratch_path(name);
  std::ofstream(path) << text;
  return path;
}

// Two fits of the Lambertian model at 500 and 600 nm; the file's best is the first.
std::string two_fits() {
  return write("two.fit.json", R"({"format": "roadbrdf-fit", "version": 1, "best": "lambert", "fits": [
    {"model": "lambert", "wavelengths": [500, 600], "parameters": {"albedo": [0.2, 0.4]}},
    {"model": "oren-nayar", "wavelengths": [500, 600], "parameters": {"albedo": [0.3, 0.5], "sigma": [0, 0]}}]})");
}

double brdf_at(const SpectralModel& model, double wavelength_nm) {
  const std::vector<double> p = model.parameters_at(wavelength_nm);
  return model.model().evaluate(p.data(), geometry_from_degrees(30.0, 0.0, 20.0, 180.0));
}

TEST(ModelSource, FitFileGivesItsBestFitAndSaysWhichEntry) {
  const ResolvedModel r = resolve_model(two_fits(), {}, {}, "");
  EXPECT_EQ(r.kind, "fit");
  EXPECT_EQ(r.entry, "lambert");
  EXPECT_NEAR(brdf_at(r.model, 600.0), 0.4 / std::numbers::pi, 1e-12);
}

TEST(ModelSource, FitSelectsAnotherEntry) {
  const ResolvedModel r = resolve_model(two_fits(), {}, {}, "oren-nayar");
  EXPECT_EQ(r.entry, "oren-nayar");
  // Oren-Nayar with sigma = 0 is the Lambertian reflector.
  EXPECT_NEAR(brdf_at(r.model, 500.0), 0.3 / std::numbers::pi, 1e-12);
}

TEST(ModelSource, ModelNameTakesItsParameters) {
  const ResolvedModel r = resolve_model("lambert", {"albedo=0.25"}, {}, "");
  EXPECT_EQ(r.kind, "model");
  EXPECT_EQ(r.entry, "lambert");
  EXPECT_NEAR(brdf_at(r.model, 550.0), 0.25 / std::numbers::pi, 1e-12);
}

TEST(ModelSource, MixFileGivesItsMethodAsAMixture) {
  const std::string mix = write("two.mix.json", R"({"format": "roadbrdf-mix", "version": 1, "best": "areal",
    "end_members": [{"name": "binder", "model": "lambert"}, {"name": "stone", "model": "lambert"}],
    "methods": [{"method": "areal", "model": "mixture-linear", "end_members": ["binder", "stone"],
                 "wavelengths": [],
                 "parameters": {"weight.binder": [0.25], "weight.stone": [0.75],
                                "binder.albedo": [0.04], "stone.albedo": [0.6]}}]})");
  const ResolvedModel r = resolve_model(mix, {}, {}, "");
  EXPECT_EQ(r.kind, "mix");
  EXPECT_EQ(r.entry, "areal");
  EXPECT_NEAR(brdf_at(r.model, 550.0), (0.25 * 0.04 + 0.75 * 0.6) / std::numbers::pi, 1e-12);
}

template <class Call>
std::string refused_field(Call call) {
  try {
    call();
  } catch (const FieldError& e) {
    return e.field();
  }
  return "(accepted)";
}

TEST(ModelSource, MisplacedFieldsAreRefusedByName) {
  const std::string fit = two_fits();
  EXPECT_EQ(refused_field([&] { resolve_model(fit, {"albedo=0.5"}, {}, ""); }), "parameters");
  EXPECT_EQ(refused_field([&] { resolve_model(fit, {}, {"form=full"}, ""); }), "options");
  EXPECT_EQ(refused_field([&] { resolve_model("lambert", {}, {}, "lambert"); }), "fit");
  EXPECT_EQ(refused_field([&] { resolve_model("lambert", {"albedo=x"}, {}, ""); }), "parameters");
  // An unknown model name is the model's error (with the nearest name), an unknown option the options'.
  EXPECT_EQ(refused_field([&] { resolve_model("lambertt", {}, {}, ""); }), "model");
  EXPECT_EQ(refused_field([&] { resolve_model("oren-nayar+lambertt", {}, {}, ""); }), "model");
  EXPECT_EQ(refused_field([&] { resolve_model("oren-nayar", {}, {"no_such_option=1"}, ""); }), "options");
  try {
    resolve_model("lambertt", {}, {}, "");
  } catch (const FieldError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'lambert'?"), std::string::npos) << e.what();
  }
  // A selection matching no fit is an error at the file's "fits" key.
  EXPECT_THROW(resolve_model(fit, {}, {}, "no-such-model"), FileError);
}

}  // namespace
}  // namespace roadbrdf
