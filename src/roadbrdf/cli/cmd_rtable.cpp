// roadbrdf rtable (FIT.json | MODEL -p ... | --import FILE) [--alpha 1] [--illuminant A|D65|FILE]
//   [--wavelength NM | --band A:B] [--format csv|rtb|radiance] [-o FILE] [--json] [--compare OTHER]
// Road-photometry r-table of a BRDF (or of an r-table file) and its summary figures Q0, S1, S2, Qd, class;
// for a fit file also their standard uncertainties and the class probabilities (rtable_uncertainty.h).
#include <fmt/core.h>

#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/common.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/fitting/fit_file.h"
#include "roadbrdf/photometry/rtable_io.h"
#include "roadbrdf/photometry/rtable_request.h"

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

std::optional<RTableFormat> import_format(const std::string& name) {
  if (name.empty()) return std::nullopt;
  return rtable_format_from_name(name, "import_format");
}

// The flags translated into the library's request (photometry/rtable_request.h owns the rules).
RTableRequest request_from(const RTableArgs& a) {
  RTableRequest request;
  request.illuminant = a.illuminant;
  request.wavelength = a.wavelength;
  if (!a.band.empty()) {
    const auto colon = a.band.find(':');
    if (colon == std::string::npos) throw InputError("--band expects A:B in nm, got '" + a.band + "'");
    request.band = {parse_number(a.band.substr(0, colon), "--band"), parse_number(a.band.substr(colon + 1), "--band")};
  }
  request.alpha = a.alpha;
  request.q0_region = a.q0_region;
  request.class_system = a.class_system;
  return request;
}

void run(const RTableArgs& a) {
  const bool from_import = !a.import_file.empty();
  if (from_import == !a.model.empty()) {
    throw InputError("give either a model (or FIT.json) or --import FILE, not both and not neither");
  }
  check_distinct_files(
      {{"MODEL", a.model}, {"--import", a.import_file}, {"--compare", a.compare_file}, {"--illuminant", a.illuminant}},
      {{"-o", a.output}});
  const RTableRequest request = request_from(a);
  RTableReport report;
  nlohmann::json source;
  if (from_import) {
    if (!a.parameters.empty() || !a.options.empty() || !a.fit_model.empty()) {
      throw InputError("--import reads a finished r-table: -p, --option and --fit do not apply");
    }
    request.validate_for_import();
    RTableFile file = read_rtable(a.import_file, import_format(a.import_format), a.alpha, a.scale);
    source = {{"import", a.import_file}, {"format", name_of(file.format)}, {"scale", a.scale}};
    report = rtable_report(std::move(file), request);
  } else {
    if (a.scale != kRScale) throw InputError("--scale applies to --import only");
    request.validate();
    const SpectralModel model = spectral_model_from_command_line(a.model, a.parameters, a.options, a.fit_model);
    report = rtable_report(model, request);
    if (is_fit_file_argument(a.model)) report.table.name = a.model + " (" + model.model().name() + ")";
    source = {{"model", model.model().name()}};
    if (is_fit_file_argument(a.model)) source["fit_file"] = a.model;
  }
  for (const std::string& note : report.notes) fmt::print(stderr, "roadbrdf: note: {}\n", name_flags(note));
  for (const std::string& warning : report.warnings) fmt::print(stderr, "roadbrdf: warning: {}\n", name_flags(warning));
  if (!a.compare_file.empty()) {
    report.compare_with(read_rtable(a.compare_file, std::nullopt, a.alpha, kRScale).table, a.compare_file);
  }

  RTableFormat out_format = RTableFormat::csv;
  if (!a.format.empty()) {
    out_format = rtable_format_from_name(a.format);
  } else if (!a.output.empty()) {
    out_format = rtable_format_from_path(a.output).value_or(RTableFormat::csv);
  }
  if (!a.output.empty()) write_rtable_file(a.output, report.table, out_format);

  if (a.json) {
    nlohmann::json j = report.to_json();
    j["source"] = source;
    if (!a.output.empty()) j["output"] = {{"file", a.output}, {"format", name_of(out_format)}};
    std::cout << roadbrdf::dump_json(j, 2) << '\n';
    return;
  }
  const std::string text = report.summary_text();
  if (!a.output.empty()) {
    std::cout << text;
    return;
  }
  // No output file: the table goes to standard output (with the summary as comments for CSV).
  if (out_format == RTableFormat::csv) {
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) std::cout << "# " << line << '\n';
  }
  write_rtable(std::cout, report.table, out_format);
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
  command->add_option("--import-format", args.import_format,
                      "Format of --import when the extension does not tell: " + names_text<RTableFormat>());
  command->add_option("--scale", args.scale, "Imported file values are r times this (default 1e4; e.g. 1 for plain r)");
  command->add_option("--alpha", args.alpha, "Observation angle above the road plane [deg] (default 1)");
  command->add_option("--illuminant", args.illuminant,
                      "Photometric weighting V(lambda) x S(lambda) of a spectral model: A (default), D65, or a "
                      "lamp spectrum CSV (wavelength_nm, relative power)");
  command->add_option("--wavelength", args.wavelength, "Use the spectral model at one wavelength [nm] instead");
  command->add_option("--band", args.band, "Use the unweighted mean over a band A:B [nm] instead");
  command->add_option("--format", args.format,
                      "Table format: " + described_names_text<RTableFormat>() + " (default csv); all store 1e4 r");
  command->add_option("-o,--output", args.output, "Write the table here (atomically); default: standard output");
  command->add_flag("--json", args.json,
                    "Print JSON: Q0, S1, S2, Qd, class, beta_deg, tan_gamma, r (plain r in sr^-1, null = missing), "
                    "uncertainty (from a fit's covariance)");
  command->add_option(
      "--compare", args.compare_file,
      "Compare with another r-table file (reference): max/mean relative difference, Q0 and S1 differences");
  command->add_option("--q0-region", args.q0_region,
                      "Q0 averaging region: " + described_names_text<Q0Region>() + " (default standard)");
  command->add_option("--class-system", args.class_system,
                      "Class reported as 'class': " + names_text<ClassSystem>() + " (default R)");
  command->callback([] { run(args); });
}

}  // namespace roadbrdf::cli
