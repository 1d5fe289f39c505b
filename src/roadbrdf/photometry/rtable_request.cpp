#include "roadbrdf/photometry/rtable_request.h"

#include <fmt/core.h>

#include <cmath>
#include <sstream>
#include <tuple>

#include "roadbrdf/core/error.h"
#include "roadbrdf/spectra/cie.h"

namespace roadbrdf::photometry {

namespace {

nlohmann::json number_or_null(double x) { return std::isnan(x) ? nlohmann::json(nullptr) : nlohmann::json(x); }

nlohmann::json class_json(const RoadClass& c) { return {{"name", c.name}, {"standard_Q0", c.standard_q0}}; }

// Q0 of real road surfaces lies between about 0.04 and 0.2 sr^-1 (van Bommel, Road Lighting,
// Table 12.2: standard tables 0.07-0.10); above this the table is most likely scaled differently.
constexpr double kImplausibleQ0 = 0.5;
// Below this (a fifth of the darkest surfaces, and of the standard classes' 0.07-0.10) the S1 class is
// given with a warning: a table that dark is a scale error of the data (BRDF x cos theta_i, percent,
// a radiance), and its class says nothing about a road.
constexpr double kImplausiblyLowQ0 = 0.01;

// The summary figures, class, coverage notes and plausibility warnings of a finished table.
void summarize_into(RTableReport& report, const RTableRequest& request,
                    const std::optional<AngularCoverage>& fit_coverage) {
  report.q0_region = request.q0_region;
  report.class_system = request.class_system;
  report.summary = summarize(report.table, request.region());
  report.chosen = classify(report.summary.s1, request.system());
  report.coverage = rtable_coverage(report.table, fit_coverage);
  for (const std::string& note : report.coverage.notes()) {
    if (note.rfind("WARNING: ", 0) == 0) {
      report.warnings.push_back(note.substr(9));
    } else {
      report.notes.push_back(note);
    }
  }
  if (report.summary.q0 > kImplausibleQ0) {
    report.warnings.push_back(
        fmt::format("Q0 = {:.4g} sr^-1 is implausibly large for a road surface: is the table "
                    "normalised differently (e.g. to Q0 = 1)? See the scale option of the import",
                    report.summary.q0));
  }
  if (report.summary.q0 >= 0.0 && report.summary.q0 < kImplausiblyLowQ0) {
    report.warnings.push_back(
        fmt::format("Q0 = {:.3g} sr^-1 is far below any road surface (0.04-0.2) and the standard tables of class "
                    "{} (Q0 {:g}): the class is not meaningful for this table; check the scale of the data (BRDF in "
                    "sr^-1, not BRDF x cos theta_i, a radiance or a reflectance in percent)",
                    report.summary.q0, report.chosen.name, report.chosen.standard_q0));
  }
  const auto& declared = report.declared_q0;
  if (declared && *declared > 0.0 && std::abs(*declared - report.summary.q0) > 0.05 * report.summary.q0) {
    report.warnings.push_back(
        fmt::format("the file declares q0 = {:.6g}, but its values (read as 1e4 r) give Q0 = "
                    "{:.6g} sr^-1",
                    *declared, report.summary.q0));
  }
}

}  // namespace

void RTableRequest::validate() const {
  if (!(alpha > 0.0 && alpha < 90.0)) {
    throw FieldError("alpha", fmt::format("must lie in (0, 90) deg, got {}", alpha));
  }
  if (wavelength && band) throw FieldError("band", "excludes a single wavelength: give one of the two");
  if (wavelength && !(std::isfinite(*wavelength) && *wavelength > 0.0)) {
    throw FieldError("wavelength", fmt::format("must be a positive wavelength [nm], got {}", *wavelength));
  }
  if (band &&
      !(std::isfinite(band->first) && std::isfinite(band->second) && band->first > 0.0 && band->first < band->second)) {
    throw FieldError("band", fmt::format("must be A:B with 0 < A < B [nm], got {}:{}", band->first, band->second));
  }
  if ((wavelength || band) && !illuminant.empty()) {
    throw FieldError("illuminant", "applies to the photometric weighting only, not with a single wavelength or a band");
  }
  region();
  system();
}

void RTableRequest::validate_for_import() const {
  validate();
  const char* field = !illuminant.empty() ? "illuminant" : wavelength ? "wavelength" : band ? "band" : "";
  if (*field) throw FieldError(field, "does not apply to an r-table read from a file (it has no spectrum)");
}

Q0Region RTableRequest::region() const { return parse_name<Q0Region>(q0_region, "q0_region"); }

ClassSystem RTableRequest::system() const { return class_system_from_name(class_system, "class_system"); }

RTableReport rtable_report(const SpectralModel& model, const RTableRequest& request) {
  return rtable_report(model, request, weighted_brdf);
}

RTableReport rtable_report(const SpectralModel& model, const RTableRequest& request, const WeightedBrdf& brdf) {
  request.validate();
  RTableReport report;
  SpectralWeighting w;
  if (request.wavelength) {
    w.kind = SpectralWeighting::Kind::wavelength;
    w.wavelength_nm = *request.wavelength;
    report.weighting = {{"kind", "wavelength"}, {"wavelength_nm", w.wavelength_nm}};
  } else if (request.band) {
    w.kind = SpectralWeighting::Kind::band;
    std::tie(w.band_lo_nm, w.band_hi_nm) = *request.band;
    report.weighting = {{"kind", "band (unweighted mean)"}, {"band_nm", {w.band_lo_nm, w.band_hi_nm}}};
  } else {
    const std::string name = request.illuminant.empty() ? std::string("A") : request.illuminant;
    // Only a spectral model needs the tables (a plain model works without the data folder).
    if (model.is_spectral()) w.illuminant = illuminant_from_name(name);
    report.weighting = {{"kind", "photometric (V(lambda) x illuminant)"}, {"illuminant", name}};
  }
  if (!model.is_spectral()) {
    if (request.wavelength || request.band || !request.illuminant.empty()) {
      report.warnings.push_back(
          "the model's parameters do not depend on wavelength: the illuminant, wavelength or band has no effect");
    }
    report.weighting = {{"kind", "none (wavelength-independent model)"}};
  } else {
    const double lo = model.wavelengths().front(), hi = model.wavelengths().back();
    std::string note;
    w = effective_weighting(model, w, &note);
    if (!note.empty()) {
      report.notes.push_back(note);
      report.weighting = {
          {"kind", "wavelength (the model's single band)"}, {"wavelength_nm", w.wavelength_nm}, {"note", note}};
    }
    report.weighting["model_wavelength_range_nm"] = {lo, hi};
    if (w.kind == SpectralWeighting::Kind::photometric) {
      const double coverage = luminous_coverage(lo, hi, *w.illuminant);
      report.weighting["luminous_coverage"] = coverage;
      if (coverage < 0.999) {
        report.warnings.push_back(
            fmt::format("the model's wavelengths ({}-{} nm) hold only {:.2f}% of the luminous "
                        "integral; the rest is left out of the weighting",
                        lo, hi, 100.0 * coverage));
      }
    }
  }
  report.table =
      rtable_from_brdf(brdf(model, w, rtable_geometries(request.alpha)), request.alpha, model.model().name());
  summarize_into(report, request, model.coverage());
  // Cheap (each parameter moves only its neighbouring wavelengths): always, as for albedo.
  report.uncertainty = summary_uncertainty(model, w, report.table, request.region());
  if (report.uncertainty && !model.shared_parameters().empty()) report.notes.push_back(shared_parameters_note(model));
  if (report.uncertainty && report.coverage.extrapolated()) {
    report.notes.push_back(
        "no class probability: every standard-region cell is extrapolated, and the fit's covariance only "
        "describes the measured directions, so u(S1) does not bound the class");
  } else if (report.uncertainty && !std::isnan(report.uncertainty->independent.s1)) {
    report.class_probabilities =
        class_probabilities(report.summary.s1, report.uncertainty->independent.s1, request.system());
  }
  return report;
}

RTableReport rtable_report(RTableFile imported, const RTableRequest& request) {
  request.validate_for_import();
  RTableReport report;
  report.table = std::move(imported.table);
  report.declared_q0 = imported.declared_q0;
  summarize_into(report, request, std::nullopt);
  return report;
}

void RTableReport::compare_with(const RTable& reference, const std::string& name) {
  comparison = compare(table, reference, parse_name<Q0Region>(q0_region, "q0_region"));
  compared_with = name;
}

nlohmann::json RTableReport::to_json() const {
  nlohmann::json j;
  j["weighting"] = weighting;
  j["alpha_deg"] = table.alpha_deg;
  j["units"] = {{"r", "reduced luminance coefficient r = q cos^3(gamma) [sr^-1], plain (NOT x1e4); null = missing"},
                {"Q0", "sr^-1"},
                {"Qd", "sr^-1"},
                {"S1", "1"},
                {"S2", "1"},
                {"beta_deg", "deg, 0 = forward side"},
                {"tan_gamma", "1"},
                {"uncertainty",
                 "standard uncertainties (units of the figures) of Q0, S1, S2, Qd from the parameter "
                 "covariance of a fit, or of a mixture from its end-members' fits, wavelengths independent; "
                 "correlated: the bound for errors fully correlated across wavelengths; class_probabilities: "
                 "the classes of class_system with probability >= 0.01 for S1 normal with that u (null when "
                 "extrapolated is true: no standard-region cell measured); null when "
                 "unknown (a model given by its parameters, a mixture fitted to measured data, an imported "
                 "table), null entries where the covariance is undefined"}};
  j["Q0"] = summary.q0;
  j["q0_region"] = q0_region;
  j["S1"] = summary.s1;
  j["S2"] = summary.s2;
  j["Qd"] = summary.qd;
  j["r00"] = summary.r00;
  j["class"] = chosen.name;
  j["class_system"] = class_system;
  j["class_standard_Q0"] = chosen.standard_q0;
  j["classes"] = {
      {"R", class_json(summary.r_class)}, {"N", class_json(summary.n_class)}, {"C", class_json(summary.c_class)}};
  j["defined_cells"] = summary.defined_cells;
  j["extrapolated"] = coverage.extrapolated();
  j["uncertainty"] = uncertainty_json();
  if (declared_q0) j["declared_q0"] = *declared_q0;
  j["beta_deg"] = standard_beta_deg();
  j["tan_gamma"] = standard_tan_gamma();
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t i = 0; i < kRows; ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (std::size_t c = 0; c < kColumns; ++c) row.push_back(number_or_null(table.r(i, c)));
    rows.push_back(row);
  }
  j["r"] = rows;
  j["coverage"] = coverage.to_json();
  j["notes"] = notes;
  j["warnings"] = warnings;
  if (!source.is_null()) j["source"] = source;
  if (!output.is_null()) j["output"] = output;
  if (comparison) {
    j["comparison"] = {{"other", compared_with},
                       {"max_relative_difference", comparison->max_relative},
                       {"max_at",
                        {{"tan_gamma", standard_tan_gamma()[comparison->max_row]},
                         {"beta_deg", standard_beta_deg()[comparison->max_column]}}},
                       {"mean_relative_difference", comparison->mean_relative},
                       {"compared_cells", comparison->compared_cells},
                       {"cells_only_here", comparison->only_in_a},
                       {"cells_only_in_other", comparison->only_in_b},
                       {"Q0_difference", comparison->q0_difference},
                       {"S1_difference", comparison->s1_difference}};
  }
  return j;
}

std::vector<ClassProbability> RTableReport::reported_classes() const {
  std::vector<ClassProbability> reported;
  for (const ClassProbability& c : class_probabilities) {
    if (c.probability >= kReportedClassProbability) reported.push_back(c);
  }
  return reported;
}

nlohmann::json RTableReport::uncertainty_json() const {
  if (!uncertainty) return nullptr;
  nlohmann::json classes = nullptr;
  if (!class_probabilities.empty()) {
    classes = nlohmann::json::array();
    for (const ClassProbability& c : reported_classes()) {
      classes.push_back({{"class", c.name}, {"probability", c.probability}});
    }
  }
  auto figures = [](const SummaryUncertainty& u) {
    return nlohmann::json{{"Q0", number_or_null(u.q0)},
                          {"S1", number_or_null(u.s1)},
                          {"S2", number_or_null(u.s2)},
                          {"Qd", number_or_null(u.qd)}};
  };
  nlohmann::json j = figures(uncertainty->independent);
  j["method"] =
      "linearised (GUM eq. 10) from the parameter covariance at each wavelength (a fit's, or a mixture's from its "
      "end-members' fits), wavelengths independent";
  j["correlated"] = figures(uncertainty->correlated);
  j["class_probabilities"] = classes;
  return j;
}

std::string RTableReport::summary_text() const {
  std::ostringstream text;
  text << fmt::format("Q0 = {:.6g} sr^-1 (region: {})\n", summary.q0, q0_region);
  text << fmt::format("S1 = {:.6g}\nS2 = {:.6g}\nQd = {:.6g} sr^-1\nr(0,0) = {:.6g} sr^-1\n", summary.s1, summary.s2,
                      summary.qd, summary.r00);
  text << fmt::format("class = {} (standard Q0 {:.2f}); R: {}, N: {}, C: {}\n", chosen.name, chosen.standard_q0,
                      summary.r_class.name, summary.n_class.name, summary.c_class.name);
  if (uncertainty) {
    auto u = [](double x) { return std::isnan(x) ? std::string("undefined") : fmt::format("{:.3g}", x); };
    const SummaryUncertainty& i = uncertainty->independent;
    const SummaryUncertainty& c = uncertainty->correlated;
    text << fmt::format(
        "u(Q0) = {} sr^-1, u(S1) = {}, u(S2) = {}, u(Qd) = {} sr^-1 (standard uncertainties from the "
        "parameter covariance)\n",
        u(i.q0), u(i.s1), u(i.s2), u(i.qd));
    text << fmt::format(
        "errors correlated across wavelengths (bound): u(Q0) = {} sr^-1, u(S1) = {}, u(S2) = {}, u(Qd) = {} "
        "sr^-1\n",
        u(c.q0), u(c.s1), u(c.s2), u(c.qd));
    if (coverage.extrapolated()) {
      text << "class probability: none (extrapolated: no standard-region cell was measured)\n";
    } else if (!class_probabilities.empty()) {
      std::string classes;
      for (const ClassProbability& c : reported_classes()) {
        classes += fmt::format("{}{} {:.3f}", classes.empty() ? "" : ", ", c.name, c.probability);
      }
      text << fmt::format("class probability ({}, S1 normal with u(S1)): {}\n", class_system, classes);
    }
  }
  text << fmt::format("defined cells = {} of {}; alpha = {} deg\n", summary.defined_cells, kRows * kColumns,
                      table.alpha_deg);
  if (declared_q0) text << fmt::format("declared q0 (file) = {:.6g}\n", *declared_q0);
  if (comparison) {
    text << fmt::format(
        "compared with {}: max relative difference {:.4g} (tan gamma {}, beta {} deg), mean {:.4g} over {} cells; "
        "cells only here {}, only there {}; Q0 difference {:.4g} sr^-1, S1 difference {:.4g}\n",
        compared_with, comparison->max_relative, standard_tan_gamma()[comparison->max_row],
        standard_beta_deg()[comparison->max_column], comparison->mean_relative, comparison->compared_cells,
        comparison->only_in_a, comparison->only_in_b, comparison->q0_difference, comparison->s1_difference);
  }
  return text.str();
}

}  // namespace roadbrdf::photometry
