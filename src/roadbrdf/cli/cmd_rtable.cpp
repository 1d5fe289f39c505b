// roadbrdf rtable (FIT.json | MODEL -p ... | --import FILE) [--alpha 1] [--illuminant A|D65|FILE]
//   [--wavelength NM | --band A:B] [--format csv|rtb|radiance] [-o FILE] [--json] [--compare OTHER]
// Road-photometry r-table of a BRDF (or of an r-table file) and its summary figures Q0, S1, S2, Qd, class.
#include <fmt/core.h>

#include <charconv>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/common.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/fitting/fit_file.h"
#include "roadbrdf/photometry/rtable.h"
#include "roadbrdf/photometry/rtable_coverage.h"
#include "roadbrdf/photometry/rtable_io.h"
#include "roadbrdf/spectra/cie.h"

namespace roadbrdf::cli {

namespace {

using namespace roadbrdf::photometry;

struct RTableArgs {
  std::string model;
  std::vector<std::string> parameters;
  std::vector<std::string> options;
  std::string fit_model;
  std::string import_file;
  std::string import_format;
  double scale = kRScale;
  double alpha = 1.0;
  std::string illuminant;
  std::optional<double> wavelength;
  std::string band;
  std::string format;
  std::string output;
  bool json = false;
  std::string compare_file;
  std::string q0_region = "standard";
  std::string class_system = "R";
};

void warn(const std::string& message) { fmt::print(stderr, "roadbrdf: warning: {}\n", message); }

Q0Region region_from_name(const std::string& name) {
  if (name == "standard") return Q0Region::standard;
  if (name == "table") return Q0Region::table;
  throw InputError("--q0-region '" + name + "' is not one of standard, table");
}

std::optional<RTableFormat> import_format(const std::string& name) {
  if (name.empty()) return std::nullopt;
  return rtable_format_from_name(name);
}

nlohmann::json class_json(const RoadClass& c) {
  return {{"name", c.name}, {"standard_Q0", c.standard_q0}};
}

nlohmann::json number_or_null(double x) { return std::isnan(x) ? nlohmann::json(nullptr) : nlohmann::json(x); }

void run(const RTableArgs& a) {
  const bool from_import = !a.import_file.empty();
  if (from_import == !a.model.empty()) {
    throw InputError("give either a model (or FIT.json) or --import FILE, not both and not neither");
  }
  if (a.wavelength && !a.band.empty()) throw InputError("--wavelength and --band exclude each other");
  if ((a.wavelength || !a.band.empty()) && !a.illuminant.empty()) {
    throw InputError("--illuminant applies to photometric weighting only; drop it with --wavelength or --band");
  }
  check_distinct_files({{"MODEL", a.model}, {"--import", a.import_file}, {"--compare", a.compare_file},
                        {"--illuminant", a.illuminant}},
                       {{"-o", a.output}});
  const Q0Region region = region_from_name(a.q0_region);
  const ClassSystem system = class_system_from_name(a.class_system);

  RTable table;
  std::optional<double> declared_q0;
  nlohmann::json source;
  nlohmann::json weighting_json = nullptr;
  std::optional<AngularCoverage> fit_coverage;  // computed tables: the fit's measured directions
  if (from_import) {
    if (!a.parameters.empty() || !a.options.empty() || !a.fit_model.empty() || !a.illuminant.empty() ||
        a.wavelength || !a.band.empty()) {
      throw InputError("--import reads a finished r-table: -p, --option, --fit, --illuminant, --wavelength and "
                       "--band do not apply");
    }
    RTableFile file = read_rtable(a.import_file, import_format(a.import_format), a.alpha, a.scale);
    table = std::move(file.table);
    declared_q0 = file.declared_q0;
    source = {{"import", a.import_file}, {"format", rtable_format_name(file.format)}, {"scale", a.scale}};
  } else {
    if (a.scale != kRScale) throw InputError("--scale applies to --import only");
    const SpectralModel model = spectral_model_from_command_line(a.model, a.parameters, a.options, a.fit_model);
    SpectralWeighting w;
    std::string weighting_text;
    if (a.wavelength) {
      w.kind = SpectralWeighting::Kind::wavelength;
      w.wavelength_nm = *a.wavelength;
      weighting_json = {{"kind", "wavelength"}, {"wavelength_nm", *a.wavelength}};
    } else if (!a.band.empty()) {
      const auto colon = a.band.find(':');
      if (colon == std::string::npos) throw InputError("--band expects A:B in nm, got '" + a.band + "'");
      w.kind = SpectralWeighting::Kind::band;
      w.band_lo_nm = parse_number(a.band.substr(0, colon), "--band");
      w.band_hi_nm = parse_number(a.band.substr(colon + 1), "--band");
      weighting_json = {{"kind", "band (unweighted mean)"}, {"band_nm", {w.band_lo_nm, w.band_hi_nm}}};
    } else {
      w.kind = SpectralWeighting::Kind::photometric;
      // Only a spectral model needs the tables (a plain model works without the data folder).
      if (model.is_spectral()) w.illuminant = illuminant_from_name(a.illuminant.empty() ? "A" : a.illuminant);
      weighting_json = {{"kind", "photometric (V(lambda) x illuminant)"},
                        {"illuminant", a.illuminant.empty() ? std::string("A") : a.illuminant}};
    }
    if (!model.is_spectral()) {
      if (a.wavelength || !a.band.empty() || !a.illuminant.empty()) {
        warn("the model's parameters do not depend on wavelength: --illuminant/--wavelength/--band have no effect");
      }
      weighting_json = {{"kind", "none (wavelength-independent model)"}};
    } else {
      const double lo = model.wavelengths().front(), hi = model.wavelengths().back();
      std::string note;
      w = effective_weighting(model, w, &note);
      if (!note.empty()) {
        fmt::print(stderr, "roadbrdf: note: {}\n", note);
        weighting_json = {{"kind", "wavelength (the model's single band)"}, {"wavelength_nm", w.wavelength_nm},
                          {"note", note}};
      }
      weighting_json["model_wavelength_range_nm"] = {lo, hi};
      if (w.kind == SpectralWeighting::Kind::photometric) {
        const double coverage = luminous_coverage(lo, hi, *w.illuminant);
        weighting_json["luminous_coverage"] = coverage;
        if (coverage < 0.999) {
          warn(fmt::format("the model's wavelengths ({}-{} nm) hold only {:.2f}% of the luminous integral; the rest is "
                           "left out of the weighting",
                           lo, hi, 100.0 * coverage));
        }
      }
    }
    table = compute_rtable(model, w, a.alpha);
    fit_coverage = model.coverage();
    if (is_fit_file_argument(a.model)) table.name = a.model + " (" + model.model().name() + ")";
    source = {{"model", model.model().name()}};
    if (is_fit_file_argument(a.model)) source["fit_file"] = a.model;
  }

  const RTableSummary summary = summarize(table, region);
  const RTableCoverage coverage = rtable_coverage(table, fit_coverage);
  for (const std::string& note : coverage.notes()) {
    if (note.rfind("WARNING: ", 0) == 0) {
      warn(note.substr(9));
    } else {
      fmt::print(stderr, "roadbrdf: note: {}\n", note);
    }
  }
  const RoadClass chosen = classify(summary.s1, system);
  if (summary.q0 > 0.5) {
    warn(fmt::format("Q0 = {:.4g} sr^-1 is implausibly large for a road surface: is the table normalised "
                     "differently (e.g. to Q0 = 1)? See --scale",
                     summary.q0));
  }
  if (declared_q0 && *declared_q0 > 0.0 && std::abs(*declared_q0 - summary.q0) > 0.05 * summary.q0) {
    warn(fmt::format("the file declares q0 = {:.6g}, but its values (read as 1e4 r) give Q0 = {:.6g} sr^-1", *declared_q0,
                     summary.q0));
  }
  std::optional<RTableComparison> comparison;
  if (!a.compare_file.empty()) {
    const RTableFile other = read_rtable(a.compare_file, std::nullopt, a.alpha, kRScale);
    comparison = compare(table, other.table, region);
  }

  RTableFormat out_format = RTableFormat::csv;
  if (!a.format.empty()) {
    out_format = rtable_format_from_name(a.format);
  } else if (!a.output.empty()) {
    out_format = rtable_format_from_path(a.output).value_or(RTableFormat::csv);
  }
  if (!a.output.empty()) write_rtable_file(a.output, table, out_format);

  if (a.json) {
    nlohmann::json j;
    j["source"] = source;
    j["weighting"] = weighting_json;
    j["alpha_deg"] = table.alpha_deg;
    j["units"] = {{"r", "reduced luminance coefficient r = q cos^3(gamma) [sr^-1], plain (NOT x1e4); null = missing"},
                  {"Q0", "sr^-1"}, {"Qd", "sr^-1"}, {"S1", "1"}, {"S2", "1"},
                  {"beta_deg", "deg, 0 = forward side"}, {"tan_gamma", "1"}};
    j["Q0"] = summary.q0;
    j["q0_region"] = a.q0_region;
    j["S1"] = summary.s1;
    j["S2"] = summary.s2;
    j["Qd"] = summary.qd;
    j["r00"] = summary.r00;
    j["class"] = chosen.name;
    j["class_system"] = a.class_system;
    j["class_standard_Q0"] = chosen.standard_q0;
    j["classes"] = {{"R", class_json(summary.r_class)}, {"N", class_json(summary.n_class)},
                    {"C", class_json(summary.c_class)}};
    j["defined_cells"] = summary.defined_cells;
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
    if (comparison) {
      j["comparison"] = {{"other", a.compare_file},
                         {"max_relative_difference", comparison->max_relative},
                         {"max_at", {{"tan_gamma", standard_tan_gamma()[comparison->max_row]},
                                     {"beta_deg", standard_beta_deg()[comparison->max_column]}}},
                         {"mean_relative_difference", comparison->mean_relative},
                         {"compared_cells", comparison->compared_cells},
                         {"cells_only_here", comparison->only_in_a},
                         {"cells_only_in_other", comparison->only_in_b},
                         {"Q0_difference", comparison->q0_difference},
                         {"S1_difference", comparison->s1_difference}};
    }
    if (!a.output.empty()) j["output"] = {{"file", a.output}, {"format", rtable_format_name(out_format)}};
    std::cout << roadbrdf::dump_json(j, 2) << '\n';
    return;
  }

  std::ostringstream text;
  text << fmt::format("Q0 = {:.6g} sr^-1 (region: {})\n", summary.q0, a.q0_region);
  text << fmt::format("S1 = {:.6g}\nS2 = {:.6g}\nQd = {:.6g} sr^-1\nr(0,0) = {:.6g} sr^-1\n", summary.s1, summary.s2,
                      summary.qd, summary.r00);
  text << fmt::format("class = {} (standard Q0 {:.2f}); R: {}, N: {}, C: {}\n", chosen.name, chosen.standard_q0,
                      summary.r_class.name, summary.n_class.name, summary.c_class.name);
  text << fmt::format("defined cells = {} of 580; alpha = {} deg\n", summary.defined_cells, table.alpha_deg);
  if (declared_q0) text << fmt::format("declared q0 (file) = {:.6g}\n", *declared_q0);
  if (comparison) {
    text << fmt::format(
        "compared with {}: max relative difference {:.4g} (tan gamma {}, beta {} deg), mean {:.4g} over {} cells; "
        "cells only here {}, only there {}; Q0 difference {:.4g} sr^-1, S1 difference {:.4g}\n",
        a.compare_file, comparison->max_relative, standard_tan_gamma()[comparison->max_row],
        standard_beta_deg()[comparison->max_column], comparison->mean_relative, comparison->compared_cells,
        comparison->only_in_a, comparison->only_in_b, comparison->q0_difference, comparison->s1_difference);
  }
  if (!a.output.empty()) {
    std::cout << text.str();
    return;
  }
  // No output file: the table goes to standard output (with the summary as comments for CSV).
  if (out_format == RTableFormat::csv) {
    std::istringstream lines(text.str());
    for (std::string line; std::getline(lines, line);) std::cout << "# " << line << '\n';
  }
  write_rtable(std::cout, table, out_format);
}

}  // namespace

void register_rtable_command(CLI::App& app) {
  static RTableArgs args;
  auto* command = app.add_subcommand(
      "rtable",
      "Road-photometry r-table (29 tan(gamma) x 20 beta, alpha = 1 deg) of a BRDF, a fit file or an r-table file, "
      "with Q0, S1, S2, Qd and the road class. Files store R = 1e4 r; --json gives plain r [sr^-1]");
  command->add_option("model", args.model, "Model name (with -p/--option) or FIT.json");
  add_model_flags(command, args.parameters, args.options);
  add_fit_flag(command, args.fit_model);
  command->add_option("--import", args.import_file,
                      "Read an r-table file instead of computing one (.csv, .rtb, .dat Radiance; 0 = missing cell)");
  command->add_option("--import-format", args.import_format, "Format of --import when the extension does not tell: csv|rtb|radiance");
  command->add_option("--scale", args.scale,
                      "Imported file values are r times this (default 1e4; e.g. 1 for plain r)");
  command->add_option("--alpha", args.alpha, "Observation angle above the road plane [deg] (default 1)");
  command->add_option("--illuminant", args.illuminant,
                      "Photometric weighting V(lambda) x S(lambda) of a spectral model: A (default), D65, or a "
                      "lamp spectrum CSV (wavelength_nm, relative power)");
  command->add_option("--wavelength", args.wavelength, "Use the spectral model at one wavelength [nm] instead");
  command->add_option("--band", args.band, "Use the unweighted mean over a band A:B [nm] instead");
  command->add_option("--format", args.format,
                      "Table format: csv (default), rtb (DIALux), radiance (Radiance data file); all store 1e4 r");
  command->add_option("-o,--output", args.output, "Write the table here (atomically); default: standard output");
  command->add_flag("--json", args.json,
                    "Print JSON: Q0, S1, S2, Qd, class, beta_deg, tan_gamma, r (plain r in sr^-1, null = missing)");
  command->add_option("--compare", args.compare_file,
                      "Compare with another r-table file (reference): max/mean relative difference, Q0 and S1 differences");
  command->add_option("--q0-region", args.q0_region,
                      "Q0 averaging region: standard (cells of the CIE standard tables, default) or table (all defined cells)");
  command->add_option("--class-system", args.class_system, "Class reported as 'class': R (default), N or C");
  command->callback([] { run(args); });
}

}  // namespace roadbrdf::cli
