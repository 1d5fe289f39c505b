// roadbrdf check DATA.csv [--json]: quality report (io/quality.h). Made by the request contract
// (cli/request_options.h; the request's table is CheckRequest::fields, io/check_request.cpp).
#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/request_options.h"
#include "roadbrdf/io/check_request.h"

namespace roadbrdf::cli {

void register_check_command(CLI::App& app) {
  static CheckRequest request;
  static bool as_json = false;
  auto* c = app.add_subcommand("check",
                               "Quality report of a dataset: angular coverage, negative/missing values, reciprocity, "
                               "noisy bands, outlier geometries, reference-panel validation");
  add_request_options(c, request);
  c->add_flag("--json", as_json, "Machine-readable report");
  c->callback([] {
    run_request<CheckRequest>([] {
      const CheckResult result = quality_check(request);
      AtomicFile out("-");
      if (as_json) {
        write_json(out.stream(), result.to_json(), 2);
        out.stream() << '\n';
      } else {
        out.stream() << request.path << '\n' << with_flags<CheckRequest>(result.summary_text());
      }
      out.commit();
    });
  });
}

}  // namespace roadbrdf::cli
