// Calibrated intimate mixing (mixing/calibration.h). Synthetic closed-form case: end-members that are
// exactly Hapke IMSA media with isotropic single scattering and known single-scattering albedos
// w_i(lambda); "measured" mixtures made here with known cross-section factors k_i through the IMSA
// reflectance written out independently (Hapke 1981 eq. 16 with p = 1, B = 0, H1), so the calibration
// must recover the k_i; and the errors for bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "mixing_test_util.h"
#include "roadbrdf/mixing/calibration.h"

namespace {

using namespace mixtest;

// Known single-scattering albedo spectra of the end-members (x = (lambda - 400) / 300).
double w_of(const std::string& name, double wavelength) {
  const double x = (wavelength - 400.0) / 300.0;
  if (name == "bright") return 0.92 - 0.10 * x;
  if (name == "mid") return 0.55 + 0.25 * x;
  if (name == "dark") return 0.12 + 0.05 * x;
  return 0.70 - 0.30 * x;  // "other"
}

// Hapke IMSA, written here: r/mu0 = (w / 4 pi) H(mu0) H(mu) / (mu0 + mu), H(x) = (1 + 2x)/(1 + 2x sqrt(1 - w)).
double imsa_reference(double w, const Geometry& g) {
  const double mu0 = g.cos_theta_i(), mu = g.cos_theta_r();
  auto H = [w](double x) { return (1.0 + 2.0 * x) / (1.0 + 2.0 * x * std::sqrt(1.0 - w)); };
  return w / (4.0 * kPi) * H(mu0) * H(mu) / (mu0 + mu);
}

// The end-member fit: the library's hapke model (H1, no opposition effect, isotropic) with w_i(lambda).
SpectralModel imsa_end_member(const std::string& name) {
  std::shared_ptr<const Model> model = make_model("hapke", {{"h_function", "hapke1981"}, {"phase", "hg"}});
  std::vector<double> table;
  for (double wl : test_wavelengths()) {
    const std::vector<double> p = parameters_from_assignments(
        model->description(), {{"w", w_of(name, wl)}, {"b0", 0.0}, {"h", 0.05}, {"xi", 0.0}});
    table.insert(table.end(), p.begin(), p.end());
  }
  return SpectralModel(model, test_wavelengths(), table);
}

struct Part {
  std::string end_member;
  double mass_percent, density;
};

const std::map<std::string, double> kDensity = {{"bright", 2.71}, {"mid", 3.45}, {"dark", 3.0}, {"other", 2.65}};

Formulation formulation_of(const std::string& name, const std::vector<std::pair<std::string, double>>& parts,
                           const std::string& folder = "") {
  Formulation f;
  f.name = name;
  for (const auto& [em, mass] : parts) {
    f.components.push_back(
        component(em, ComponentKind::kAggregate, mass, kDensity.at(em), 0.075, 0.150, folder + em + ".fit.json"));
  }
  return f;
}

FitLoader loader() {
  std::map<std::string, SpectralModel> models;
  for (const char* n : {"bright", "mid", "dark", "other"}) {
    models.emplace(std::string(n) + ".fit.json", imsa_end_member(n));
    models.emplace(std::string("elsewhere/") + n + ".fit.json", imsa_end_member(n));
  }
  return memory_loader(models);
}

// The measured mixture: w_mix = sum k_i (M_i / rho_i) w_i / sum k_i (M_i / rho_i) (one size class, so D
// cancels), then the IMSA reflectance of w_mix.
SpectralDataset measured(const Formulation& f, const std::map<std::string, double>& k) {
  return make_dataset([&](const Geometry& g, double wl) {
    double num = 0.0, den = 0.0;
    for (const Component& c : f.components) {
      const double x = k.at(c.name) * c.mass_percent / c.density;
      num += x * w_of(c.name, wl);
      den += x;
    }
    return imsa_reference(num / den, g);
  });
}

const std::map<std::string, double> kTrue = {{"bright", 1.0}, {"mid", 2.5}, {"dark", 0.4}};

struct Set {
  std::vector<MixInputs> inputs;
  std::vector<SpectralDataset> data;
  std::vector<CalibrationMixture> mixtures() const {
    std::vector<CalibrationMixture> m;
    for (std::size_t i = 0; i < inputs.size(); ++i) m.push_back({inputs[i].formulation.name, &inputs[i], &data[i]});
    return m;
  }
};

Set synthetic_set(const std::map<std::string, double>& k = kTrue) {
  Set s;
  const std::vector<Formulation> fs = {formulation_of("BM", {{"bright", 60}, {"mid", 40}}),
                                       formulation_of("BD", {{"bright", 30}, {"dark", 70}}),
                                       formulation_of("MD", {{"mid", 50}, {"dark", 50}}),
                                       formulation_of("BMD", {{"bright", 20}, {"mid", 30}, {"dark", 50}})};
  s.inputs.reserve(fs.size());
  for (const Formulation& f : fs) {
    s.inputs.push_back(load_mix_inputs(f, loader()));
    s.data.push_back(measured(f, k));
  }
  return s;
}

TEST(CrossSectionCalibration, RecoversKnownFactors) {
  const Set s = synthetic_set();
  const CrossSectionCalibration cal = calibrate_cross_sections(s.mixtures(), "bright");
  ASSERT_EQ(cal.end_members, (std::vector<std::string>{"bright", "mid", "dark"}));
  EXPECT_EQ(cal.reference, "bright");
  for (std::size_t i = 0; i < cal.end_members.size(); ++i) {
    EXPECT_NEAR(cal.factors[i], kTrue.at(cal.end_members[i]), 1e-6 * kTrue.at(cal.end_members[i]))
        << cal.end_members[i];
  }
  EXPECT_EQ(cal.factors[0], 1.0);
  EXPECT_EQ(cal.standard_errors[0], 0.0);
  // Exact data: the standard errors are tiny, the calibrated RMS is zero, the uncalibrated one is not.
  EXPECT_LT(cal.standard_errors[1], 1e-6);
  EXPECT_LT(cal.rms_calibrated_all, 1e-9);
  EXPECT_GT(cal.rms_uncalibrated_all, 1e-3);
  ASSERT_EQ(cal.rms_calibrated.size(), 4u);
  EXPECT_EQ(cal.residual_count, 4 * test_geometries().size() * test_wavelengths().size());
}

TEST(CrossSectionCalibration, OtherReferenceGivesTheSameRatios) {
  const Set s = synthetic_set();
  const CrossSectionCalibration cal = calibrate_cross_sections(s.mixtures(), "mid");
  EXPECT_NEAR(cal.factors[0], 1.0 / 2.5, 1e-6 / 2.5);  // bright / mid
  EXPECT_EQ(cal.factors[1], 1.0);
  EXPECT_NEAR(cal.factors[2], 0.4 / 2.5, 1e-6 * 0.4 / 2.5);
  // Default reference: the first end-member of the first mixture.
  EXPECT_EQ(calibrate_cross_sections(s.mixtures()).reference, "bright");
}

TEST(CrossSectionCalibration, MixWithFactorsPredictsAHeldOutMixture) {
  // Calibrate on three mixtures, predict the fourth (BMD) with `mix` and the fitted factors.
  Set s = synthetic_set();
  std::vector<CalibrationMixture> training = s.mixtures();
  training.pop_back();
  const CrossSectionCalibration cal = calibrate_cross_sections(training);
  MixSettings settings;
  for (std::size_t i = 0; i < cal.end_members.size(); ++i)
    settings.cross_section_factors[cal.end_members[i]] = cal.factors[i];
  const MixResult r = mix(s.inputs[3], Method::kHapke, settings);
  const Formulation& f = s.inputs[3].formulation;
  for (const Geometry& g : test_geometries()) {
    for (double wl : test_wavelengths()) {
      double num = 0.0, den = 0.0;
      for (const Component& c : f.components) {
        const double x = kTrue.at(c.name) * c.mass_percent / c.density;
        num += x * w_of(c.name, wl);
        den += x;
      }
      const double expected = imsa_reference(num / den, g);
      EXPECT_NEAR(value_at(*r.model, g, wl), expected, 1e-7 * expected);
    }
  }
  EXPECT_EQ(r.settings.at("cross_section_factor.mid"), cal.factors[1]);
  EXPECT_LT(hapke_reflectance_rms(s.inputs[3], settings, s.data[3]), 1e-8);
  EXPECT_GT(hapke_reflectance_rms(s.inputs[3], {}, s.data[3]), 1e-3);
  // Every end-member of the mixture needs a factor once factors are given.
  MixSettings partial;
  partial.cross_section_factors = {{"bright", 1.0}, {"mid", 2.0}};
  EXPECT_THROW(mix(s.inputs[3], Method::kHapke, partial), InputError);
}

std::string field_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const FieldError& e) {
    return e.field();
  }
  return "(no FieldError)";
}

TEST(CrossSectionCalibration, BadInputNamesTheField) {
  const Set s = synthetic_set();
  EXPECT_EQ(field_of([] { calibrate_cross_sections({}); }), "mixtures");
  EXPECT_EQ(field_of([&] { calibrate_cross_sections(s.mixtures(), "granite"); }), "reference");
  // A mixture without its data.
  std::vector<CalibrationMixture> no_data = s.mixtures();
  no_data[1].data = nullptr;
  EXPECT_EQ(field_of([&] { calibrate_cross_sections(no_data); }), "mixtures");
  // The same end-member name for two different fit files.
  const MixInputs moved = load_mix_inputs(formulation_of("BMx", {{"bright", 50}, {"mid", 50}}, "elsewhere/"), loader());
  std::vector<CalibrationMixture> mismatched = s.mixtures();
  mismatched.push_back({"BMx", &moved, &s.data[0]});
  EXPECT_EQ(field_of([&] { calibrate_cross_sections(mismatched); }), "mixtures");
  // End-members never linked by a mixture: {bright, mid} and {dark, other}.
  const MixInputs bm = load_mix_inputs(formulation_of("BM", {{"bright", 60}, {"mid", 40}}), loader());
  const MixInputs od = load_mix_inputs(formulation_of("OD", {{"other", 60}, {"dark", 40}}), loader());
  const SpectralDataset d_bm = measured(bm.formulation, {{"bright", 1.0}, {"mid", 1.0}});
  const SpectralDataset d_od = measured(od.formulation, {{"other", 1.0}, {"dark", 1.0}});
  EXPECT_EQ(field_of([&] { calibrate_cross_sections({{"BM", &bm, &d_bm}, {"OD", &od, &d_od}}); }), "mixtures");
  // A single end-member: nothing to calibrate.
  const MixInputs b = load_mix_inputs(formulation_of("B", {{"bright", 100}}), loader());
  const SpectralDataset d_b = measured(b.formulation, {{"bright", 1.0}});
  EXPECT_EQ(field_of([&] { calibrate_cross_sections({{"B", &b, &d_b}}); }), "mixtures");
  // Data outside the end-members' wavelengths.
  SpectralDataset far = s.data[0];
  far.wavelengths = {900.0, 1000.0, 1100.0, 1200.0};
  EXPECT_EQ(field_of([&] { calibrate_cross_sections({{"BM", &s.inputs[0], &far}}); }), "mixtures");
  // Requests.
  CrossSectionRequest request;
  EXPECT_EQ(field_of([&] { request.validate(); }), "mixtures");
  request.mixtures = {"a.json", "a.csv", "b.json"};  // the last formulation has no data
  EXPECT_EQ(field_of([&] { request.validate(); }), "mixtures");
  EXPECT_EQ(field_of([] { validate_cross_section_factors({{"a", -1.0}}, "cross_sections"); }), "cross_sections");
}

TEST(CrossSectionCalibration, FileRoundTripAndErrorsNameTheKey) {
  const Set s = synthetic_set();
  CrossSectionFile content;
  content.calibration = calibrate_cross_sections(s.mixtures());
  const std::string dir = ::testing::TempDir();
  const std::string path = dir + "/cross_sections_test.json";
  write_cross_section_file(path, content);
  const std::map<std::string, double> k = read_cross_section_factors(path);
  ASSERT_EQ(k.size(), 3u);
  EXPECT_EQ(k.at("mid"), content.calibration.factors[1]);
  EXPECT_EQ(k.at("bright"), 1.0);

  const std::string bad = dir + "/cross_sections_bad.json";
  auto expect_error = [&](const std::string& text, const std::string& where) {
    {
      std::ofstream out(bad);
      out << text;
    }
    try {
      read_cross_section_factors(bad);
      ADD_FAILURE() << "no error for " << text;
    } catch (const FileError& e) {
      EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  };
  expect_error(R"({"format": "roadbrdf-cross-sections", "version": 1,
                   "end_members": [{"name": "a", "cross_section_factor": 1}, {"name": "b", "cross_section_factor": -2}]})",
               "end_members[1].cross_section_factor");
  expect_error(R"({"format": "roadbrdf-mix", "version": 1, "end_members": []})", "format");
  expect_error(R"({"format": "roadbrdf-cross-sections", "version": 1, "end_members": [{"name": "a", "factor": 1}]})",
               "end_members[0]");
  expect_error(R"({"format": "roadbrdf-cross-sections", "version": 1, "reference": "z",
                   "end_members": [{"name": "a", "cross_section_factor": 1}]})",
               "reference");
  std::remove(path.c_str());
  std::remove(bad.c_str());
}

}  // namespace
