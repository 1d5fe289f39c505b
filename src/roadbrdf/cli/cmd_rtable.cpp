// roadbrdf rtable (FIT.json | MODEL -p ... | --import FILE) [--alpha 1] [--illuminant A|D65|FILE]
//   [--wavelength NM | --band A:B] [--format csv|rtb|radiance] [-o FILE] [--json] [--compare OTHER]
// Road-photometry r-table of a BRDF (or of an r-table file) and its summary figures Q0, S1, S2, Qd, class;
// for a fit file also their standard uncertainties and the class probabilities (rtable_uncertainty.h).
// Made by the request contract (cli/request_options.h; the request's table is in photometry/rtable_task.cpp).
#include <iostream>
#include <sstream>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/request_options.h"
#include "roadbrdf/photometry/rtable_request.h"

namespace roadbrdf::cli {

namespace {

using photometry::RTableRequest;

struct RTableArgs {
  RTableRequest request;
  bool json = false;
};

void run(const RTableArgs& a) {
  photometry::RTableReport report;
  run_request<RTableRequest>([&] { report = photometry::rtable(a.request); });
  for (const std::string& note : report.notes) {
    fmt::print(stderr, "roadbrdf: note: {}\n", with_flags<RTableRequest>(note));
  }
  for (const std::string& warning : report.warnings) {
    fmt::print(stderr, "roadbrdf: warning: {}\n", with_flags<RTableRequest>(warning));
  }
  AtomicFile out("-");
  if (a.json) {
    out.stream() << dump_json(report.to_json(), 2) << '\n';
  } else if (!a.request.output.empty()) {
    out.stream() << report.summary_text();
  } else {
    // No output file: the table goes to standard output (with the summary as comments for CSV).
    const photometry::RTableFormat format = a.request.output_format();
    if (format == photometry::RTableFormat::csv) {
      std::istringstream lines(report.summary_text());
      for (std::string line; std::getline(lines, line);) out.stream() << "# " << line << '\n';
    }
    photometry::write_rtable(out.stream(), report.table, format);
  }
  out.commit();
}

}  // namespace

void register_rtable_command(CLI::App& app) {
  static RTableArgs args;
  auto* command = app.add_subcommand(
      "rtable",
      "Road-photometry r-table (29 tan(gamma) x 20 beta, alpha = 1 deg) of a BRDF, a fit file or an r-table file, "
      "with Q0, S1, S2, Qd and the road class. Files store R = 1e4 r; --json gives plain r [sr^-1]");
  add_request_options(command, args.request);
  refuse_fit_model_flag(command);
  command->add_flag("--json", args.json,
                    "Print JSON: Q0, S1, S2, Qd, class, beta_deg, tan_gamma, r (plain r in sr^-1, null = missing), "
                    "uncertainty (from a fit's covariance)");
  command->callback([] { run(args); });
}

}  // namespace roadbrdf::cli
