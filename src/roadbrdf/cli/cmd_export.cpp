// roadbrdf export (FIT.json | MIX.json | MODEL -p ...) --format openmaterial3d|csv|alta
//   [--preset camera|lidar | --wavelengths ...] [--theta-i ...] [--theta-r ...] [--phi ...] -o FILE [--json]
// A model's BRDF on a grid, for other tools (io/model_export.h; the request contract of
// core/request_fields.h).
#include <fmt/core.h>

#include <iostream>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/request_options.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/io/model_export.h"

namespace roadbrdf::cli {

namespace {

struct ExportArgs {
  ExportRequest request;
  bool json = false;
};

void run(const ExportArgs& a) {
  ExportResult result;
  run_request<ExportRequest>([&] {
    check_request_files(a.request);
    result = export_model(a.request);
  });
  print_diagnostics<ExportRequest>(result.diagnostics);
  // The summary goes to standard error when the table went to standard output.
  std::FILE* report = report_stream(a.request.output);
  if (a.json) {
    fmt::print(report, "{}\n", dump_json(result.to_json(), 2));
  } else {
    fmt::print(report, "{}", result.summary_text());
  }
}

}  // namespace

void register_export_command(CLI::App& app) {
  static ExportArgs args;
  auto* c = app.add_subcommand("export",
                               "A model's BRDF on a grid as an OpenMATERIAL 3D look-up table, a CSV dataset or ALTA "
                               "text data");
  add_request_options(c, args.request);
  c->add_flag("--json", args.json, "Machine-readable result");
  c->callback([] { run(args); });
}

}  // namespace roadbrdf::cli
