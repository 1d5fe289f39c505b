// Geometry selection and grouping (io/geometry_selection.h), fits by group (`fit --group-by`,
// `--where`), grouped fit files and their selectors, and the parameter table (`roadbrdf params`).
//
// References are the parameters the synthetic data were made with: each incidence group is made
// with its own Oren-Nayar albedo and roughness, so a correct per-group fit recovers them exactly, and
// geometries outside a selection are corrupted, so only a fit that leaves them out recovers the
// parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/fitting/fit_file.h"
#include "roadbrdf/fitting/fit_request.h"
#include "roadbrdf/fitting/params_table.h"
#include "roadbrdf/io/geometry_selection.h"
#include "roadbrdf/models/registry.h"
#include "support/scratch.h"
#include "synthetic.h"

namespace roadbrdf {
namespace {

std::string field_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const FieldError& e) {
    return e.field() + ": " + e.detail();
  }
  return "no FieldError";
}

TEST(GeometrySelection, ComparisonsWithToleranceAndBothSeparators) {
  const Geometry g = geometry_from_degrees(40.0, 0.0, 70.0 - 1e-9, 180.0);
  EXPECT_TRUE(parse_geometry_selection("theta_r<=70").matches(g));
  EXPECT_TRUE(parse_geometry_selection("theta_r = 70").matches(g));  // within 1e-6 deg
  EXPECT_FALSE(parse_geometry_selection("theta_r<70").matches(g));   // equal is not less
  EXPECT_TRUE(parse_geometry_selection("theta_i>=40, theta_r<80").matches(g));
  EXPECT_TRUE(parse_geometry_selection("theta_i>30 and phi_r==180").matches(g));
  EXPECT_FALSE(parse_geometry_selection("theta_i>30 and phi_r!=180").matches(g));
  // Road angles (core/geometry.h): alpha = 90 - theta_r, beta = 180 - (phi_r - phi_i).
  EXPECT_TRUE(parse_geometry_selection("alpha=20,beta=0,gamma=40").matches(g));
  // Azimuths are folded to [0, 360): -90 is 270.
  EXPECT_TRUE(parse_geometry_selection("phi_r=270").matches(geometry_from_degrees(10, 0, 20, -90)));
}

TEST(GeometrySelection, ErrorsNameTheFieldAndTheCharacter) {
  EXPECT_EQ(field_error([] { parse_geometry_selection("theta_r<=70,thetai>3"); }),
            "where: unknown column 'thetai' (did you mean 'theta_i'?); columns: theta_i, phi_i, theta_r, phi_r, "
            "gamma, alpha, beta, delta at character 13 of 'theta_r<=70,thetai>3'");
  EXPECT_NE(field_error([] { parse_geometry_selection("theta_r 70"); }).find("expected a comparison"),
            std::string::npos);
  EXPECT_NE(field_error([] { parse_geometry_selection("theta_r<=abc"); }).find("at character 10"), std::string::npos);
  EXPECT_NE(field_error([] { parse_geometry_selection("theta_r<=70,"); }).find("after the separator"),
            std::string::npos);
  EXPECT_NE(field_error([] { parse_geometry_selection("theta_r<=70 theta_i>3"); }).find("',' or 'and'"),
            std::string::npos);
  EXPECT_NE(field_error([] { parse_geometry_selection(" "); }).find("empty selection"), std::string::npos);
}

TEST(GeometryGroups, GroupsAreOrderedAndTolerant) {
  const std::vector<Geometry> g = {geometry_from_degrees(40, 0, 10, 0), geometry_from_degrees(20, 0, 10, 0),
                                   geometry_from_degrees(40 + 1e-9, 360 - 1e-9, 30, 0),
                                   geometry_from_degrees(20, 90, 30, 0)};
  const auto by_incidence = group_geometries(g, {"theta_i"});
  ASSERT_EQ(by_incidence.size(), 2U);
  EXPECT_EQ(by_incidence[0].label(), "theta_i=20");
  EXPECT_EQ(by_incidence[0].indices, (std::vector<std::size_t>{1, 3}));
  EXPECT_EQ(by_incidence[1].indices, (std::vector<std::size_t>{0, 2}));
  const auto by_two = group_geometries(g, {"theta_i", "phi_i"});
  ASSERT_EQ(by_two.size(), 3U);  // phi_i 360 - 1e-9 folds to 0
  EXPECT_EQ(by_two[0].label(), "theta_i=20,phi_i=0");
  EXPECT_EQ(by_two[1].label(), "theta_i=20,phi_i=90");
  EXPECT_EQ(by_two[2].indices, (std::vector<std::size_t>{0, 2}));
  EXPECT_EQ(group_geometries(g, {}).size(), 1U);
  EXPECT_EQ(field_error([&] {
              group_geometries(g, {"theta_i", "theta_i"});
            }),
            "group_by: column 'theta_i' given twice");
  EXPECT_EQ(field_error([&] { group_geometries(g, {"thta_i"}); }),
            "group_by: unknown column 'thta_i' (did you mean 'theta_i'?)");
}

// Oren-Nayar data whose parameters depend on the incidence group: albedo 0.1 + 0.004 theta_i,
// sigma 0.1 + 0.005 theta_i (theta_i in degrees; inside the fitting range of sigma). No group at normal incidence:
// there the model is the same at every viewing direction, and albedo and sigma cannot be told apart. Geometries with
// theta_r > 70 are multiplied by `corrupt_grazing` (1: untouched).
struct GroupedData {
  std::shared_ptr<const Model> model = make_model("oren-nayar");
  SpectralDataset data;
  static double albedo(double theta_i) { return 0.1 + 0.004 * theta_i; }
  static double sigma(double theta_i) { return 0.1 + 0.005 * theta_i; }
  explicit GroupedData(double corrupt_grazing = 1.0) {
    data.wavelengths = {500.0, 600.0};
    for (double ti : {10.0, 20.0, 40.0, 60.0}) {
      for (double tr : {0.0, 15.0, 30.0, 45.0, 60.0, 75.0}) {
        for (double pr : {0.0, 90.0, 180.0}) {
          const Geometry g = geometry_from_degrees(ti, 0.0, tr, pr);
          data.geometries.push_back(g);
          const ModelDescription& md = model->description();
          std::vector<double> p = md.default_parameters();
          p[*md.parameter_index("albedo")] = albedo(ti);
          p[*md.parameter_index("sigma")] = sigma(ti);
          const double f = model->evaluate(p.data(), g) * (tr > 70.0 ? corrupt_grazing : 1.0);
          data.brdf.push_back(f);
          data.brdf.push_back(f);
        }
      }
    }
  }
};

TEST(FitGroups, EachIncidenceGroupRecoversItsOwnParameters) {
  GroupedData d;
  FitRequest r;
  r.models = {"oren-nayar", "lambert"};
  r.group_by = {"theta_i"};
  const FitSummary s = run_fit(r, d.data);
  ASSERT_EQ(s.fits.size(), 8U);  // 4 groups x 2 models
  EXPECT_EQ(s.group_count, 4U);
  EXPECT_EQ(s.geometry_count, d.data.geometry_count());
  const double incidences[] = {10.0, 20.0, 40.0, 60.0};
  for (std::size_t g = 0; g < 4; ++g) {
    const FitResult& on = s.fits[2 * g];
    ASSERT_EQ(on.model, "oren-nayar");
    ASSERT_EQ(on.group.size(), 1U);
    EXPECT_EQ(on.group[0].first, "theta_i");
    EXPECT_DOUBLE_EQ(on.group[0].second, incidences[g]);
    for (const auto& w : on.wavelengths) {
      EXPECT_NEAR(w.parameters[0], GroupedData::albedo(incidences[g]), 1e-6) << g;
      EXPECT_NEAR(w.parameters[1], GroupedData::sigma(incidences[g]), 1e-4) << g;
      EXPECT_EQ(w.points, 18U);
    }
    // Ranking is within the group: Oren-Nayar (exact) before Lambert.
    EXPECT_EQ(s.ranking[2 * g], 2 * g);
  }
  // One fit of all groups cannot match every group's albedo: the grouping is what recovers them.
  FitRequest whole = r;
  whole.group_by.clear();
  const FitSummary all = run_fit(whole, d.data);
  EXPECT_GT(std::abs(all.fits[0].wavelengths[0].parameters[0] - GroupedData::albedo(10.0)), 0.01);
  EXPECT_NE(s.table().find("grouped by theta_i: 4 groups"), std::string::npos);
}

TEST(FitGroups, WhereLeavesOutTheCorruptedGeometries) {
  GroupedData d(3.0);  // theta_r = 75 geometries three times too bright
  FitRequest r;
  r.models = {"oren-nayar"};
  r.group_by = {"theta_i"};
  r.where = "theta_r<=70";
  const FitSummary s = run_fit(r, d.data);
  EXPECT_EQ(s.geometry_count, 4U * 5U * 3U);
  EXPECT_EQ(s.dataset_geometries, d.data.geometry_count());
  EXPECT_NEAR(s.fits[3].wavelengths[0].parameters[0], GroupedData::albedo(60.0), 1e-6);
  r.where.clear();
  const FitSummary corrupted = run_fit(r, d.data);
  EXPECT_GT(std::abs(corrupted.fits[3].wavelengths[0].parameters[0] - GroupedData::albedo(60.0)), 0.01);
  EXPECT_NE(s.table().find("# where theta_r<=70: 60 of 72 geometries"), std::string::npos);

  FitRequest none = r;
  none.where = "theta_r>80";
  EXPECT_EQ(field_error([&] { run_fit(none, d.data); }), "where: 'theta_r>80' selects none of the 72 geometries");
  FitRequest bad = r;
  bad.where = "theta_x<3";
  EXPECT_NE(field_error([&] { bad.validate(); }).find("where: unknown column 'theta_x'"), std::string::npos);
}

TEST(FitGroups, AGroupWithTooFewPointsIsNamed) {
  GroupedData d;
  FitRequest r;
  r.models = {"oren-nayar"};
  r.group_by = {"theta_i", "theta_r", "phi_r"};  // one geometry per group: 1 point, 2 parameters
  const std::string e = field_error([&] { run_fit(r, d.data); });
  EXPECT_NE(e.find("group_by: group theta_i=10,theta_r=0,phi_r=0 (1 geometries)"), std::string::npos) << e;
}

TEST(FitGroups, GroupedFitFileSelectorsAndParameterTable) {
  GroupedData d;
  FitRequest r;
  r.models = {"oren-nayar", "lambert"};
  r.group_by = {"theta_i"};
  const FitSummary s = run_fit(r, d.data);
  const std::string path = test::scratch_path("grouped_fit.json");
  write_fit_file(path, s.fits);
  {
    std::ifstream in(path);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("\"version\": 2"), std::string::npos);
    EXPECT_NE(text.find("\"group_by\""), std::string::npos);
  }
  // A selector names the model and the group; the model alone is ambiguous in a grouped file.
  const SpectralModel m40 = read_fit_file(path, "oren-nayar,theta_i=40");
  const std::vector<double> p = m40.parameters_at(600.0);
  EXPECT_NEAR(p[0], GroupedData::albedo(40.0), 1e-6);
  EXPECT_NEAR(read_fit_file(path, "theta_i=20").parameters_at(500.0)[0], GroupedData::albedo(20.0), 1e-6);
  const std::string ambiguous = field_error([&] { read_fit_file(path, "oren-nayar"); });
  EXPECT_NE(ambiguous.find("holds 4 fits of oren-nayar, one per group (theta_i=10 theta_i=20 theta_i=40 theta_i=60)"),
            std::string::npos)
      << ambiguous;
  EXPECT_NE(field_error([&] { read_fit_file(path, "lambert,theta_i=30"); }).find("no fit of lambert for group"),
            std::string::npos);
  EXPECT_NE(field_error([&] { read_fit_file(path, "lambert,phi_i=0"); }).find("grouped by theta_i"), std::string::npos);

  // The parameter table: one row per fit at the wavelength asked for, values as generated.
  ParamsRequest q;
  q.fit_file = path;
  q.wavelengths = {590.0};  // not fitted: answered by 600 nm with a note
  q.models = {"oren-nayar"};
  const ParamsTable t = read_params_table(q);
  ASSERT_EQ(t.rows.size(), 4U);
  ASSERT_EQ(t.notes.size(), 1U);
  EXPECT_EQ(t.notes[0], "590 nm: nearest band 600 nm");
  EXPECT_EQ(t.group_columns, (std::vector<std::string>{"theta_i"}));
  EXPECT_EQ(t.parameter_names, (std::vector<std::string>{"albedo", "sigma"}));
  for (const ParamsRow& row : t.rows) {
    EXPECT_DOUBLE_EQ(row.wavelength, 600.0);
    EXPECT_NEAR(row.values[0], GroupedData::albedo(row.group[0]), 1e-6);
    EXPECT_NEAR(row.values[1], GroupedData::sigma(row.group[0]), 1e-4);
    EXPECT_LT(row.rmse, 1e-8);
    EXPECT_TRUE(row.converged);
  }
  // CSV: every number at 10 digits, parsed back equal to the fit's values.
  const std::string csv = t.render(ParamsFormat::kCsv);
  std::istringstream lines(csv);
  std::string line, header;
  std::getline(lines, line);
  EXPECT_EQ(line.rfind("# roadbrdf params of ", 0), 0U);
  std::getline(lines, line);
  EXPECT_EQ(line, "# note: 590 nm: nearest band 600 nm");
  std::getline(lines, header);
  EXPECT_EQ(header.rfind("model,theta_i_deg,wavelength_nm,albedo,albedo_stderr,sigma,sigma_stderr,rmse_per_sr", 0), 0U);
  std::getline(lines, line);
  EXPECT_EQ(line.rfind("oren-nayar,10,600,0.14", 0), 0U) << line;  // albedo(10) = 0.14
  // Markdown and LaTeX carry the values with their standard errors.
  EXPECT_NE(t.render(ParamsFormat::kMarkdown).find("| oren-nayar | 40 "), std::string::npos);
  EXPECT_NE(t.render(ParamsFormat::kLatex).find("\\begin{tabular}"), std::string::npos);
  EXPECT_EQ(field_error([] { parse_name<ParamsFormat>("latx", "format"); }),
            "format: 'latx' is not one of table, csv, markdown, latex (did you mean 'latex'?)");
}

TEST(FitBands, ABandIsTheMeanOfTheLinearSpectrumFittedAtItsCentre) {
  // Lambert data with an albedo that is not linear in wavelength, on a 20 nm grid. The band 590-610 nm
  // is the mean of the piecewise-linear spectrum over the band: by the trapezoid rule on the pieces
  // 590-600 and 600-610, (a(590) + 2 a(600) + a(610)) / 4 with a(590) = (a(580) + a(600)) / 2 and
  // a(610) = (a(600) + a(620)) / 2, i.e. (a580 + 6 a600 + a620) / 8. Lambert is linear in its albedo,
  // so the fit recovers that mean exactly.
  const auto lambert = make_model("lambert");
  const std::vector<double> wavelengths = {560, 580, 600, 620, 640};
  auto albedo = [&](std::size_t w) { return 0.05 + 1e-6 * std::pow(wavelengths[w] - 500.0, 2); };
  const SpectralDataset data = test::synthetic_dataset(
      *lambert, test::test_grid(3, 3, 3), wavelengths, [&](std::size_t w) { return std::vector<double>{albedo(w)}; },
      0.0, 0.0, 1);
  FitRequest request;
  request.models = {"lambert"};
  request.bands = {{590.0, 610.0}, {620.0, 640.0}};
  const FitSummary s = run_fit(request, data);
  ASSERT_EQ(s.wavelengths, (std::vector<double>{600.0, 630.0}));
  const double expected = (albedo(1) + 6 * albedo(2) + albedo(3)) / 8;
  EXPECT_NEAR(s.fits[0].wavelengths[0].parameters[0], expected, 1e-12);
  // 620-640 holds no interior sample: the plain mean of its two ends.
  EXPECT_NEAR(s.fits[0].wavelengths[1].parameters[0], (albedo(3) + albedo(4)) / 2, 1e-12);
  ASSERT_EQ(s.notes.size(), 2u);
  EXPECT_NE(s.notes[0].find("590-610 nm: the mean over the band"), std::string::npos) << s.notes[0];
  EXPECT_NE(s.notes[0].find("(3 measured bands, 580-620 nm)"), std::string::npos) << s.notes[0];
  EXPECT_NE(s.notes[0].find("fitted at 600 nm"), std::string::npos) << s.notes[0];
  // The residuals file fits the same spectra.
  EXPECT_EQ(fitted_spectra(request, data).wavelengths, s.wavelengths);

  request.wavelengths = {600};
  EXPECT_EQ(field_error([&] { request.validate(); }), "bands: give wavelengths or bands, not both");
  request.wavelengths.clear();
  request.bands = {{590.0, 610.0}, {600.0, 620.0}};
  EXPECT_EQ(field_error([&] { request.validate(); }), "bands: 600:620 nm overlaps 590:610 nm");
  request.bands = {{610.0, 610.0}};
  EXPECT_EQ(field_error([&] { request.validate(); }), "bands: 610:610 nm is not a band 0 < lower < upper");
  request.bands = {{620.0, 700.0}};
  EXPECT_EQ(field_error([&] { run_fit(request, data); }).rfind("bands: ", 0), 0u);
}

}  // namespace
}  // namespace roadbrdf
