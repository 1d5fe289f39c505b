// roadbrdf marking (FIT.json | MIX.json | MODEL -p ... | DATA) [--json]
// Road-marking figures of EN 1436: R_L, Q_d, the luminance factor beta and the classes
// (photometry/marking_request.h; the request contract of core/request_fields.h), and with a pavement
// the contrast against it (lighting/marking_contrast.h).
#include <fmt/core.h>

#include <iostream>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/request_options.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/lighting/marking_contrast.h"

namespace roadbrdf::cli {

namespace {

struct MarkingArgs {
  photometry::MarkingRequest request;
  bool json = false;
};

void run(const MarkingArgs& a) {
  photometry::MarkingResult result;
  run_request<photometry::MarkingRequest>([&] {
    check_request_files(a.request);
    result = lighting::marking(a.request);
  });
  print_diagnostics<photometry::MarkingRequest>(result.diagnostics);
  if (a.json) {
    std::cout << dump_json(result.to_json(), 2) << '\n';
  } else {
    std::cout << result.summary_text();
  }
}

}  // namespace

void register_marking_command(CLI::App& app) {
  static MarkingArgs args;
  auto* c = app.add_subcommand(
      "marking",
      "Road-marking photometry (EN 1436): R_L at the 30 m geometry, Q_d, beta and their classes; the contrast "
      "against a pavement");
  add_request_options(c, args.request);
  c->add_flag("--json", args.json, "Machine-readable result");
  c->callback([] { run(args); });
}

}  // namespace roadbrdf::cli
