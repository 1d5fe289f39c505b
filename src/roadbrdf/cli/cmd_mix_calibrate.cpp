// roadbrdf mix-calibrate FORMULATION.json DATA.csv [FORMULATION.json DATA.csv ...] [--reference NAME]
//                        -o CAL.json
// Fits the effective cross-section factors of the hapke mixing method's end-members to measured
// mixtures (mixing/calibration.h); `roadbrdf mix --method hapke --cross-sections CAL.json` uses them.
// Made by the request contract (cli/request_options.h; the request's table is
// CrossSectionRequest::fields, mixing/cross_section_file.cpp).
#include <fmt/core.h>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/request_options.h"
#include "roadbrdf/mixing/calibration.h"

namespace roadbrdf::cli {

void register_mix_calibrate_command(CLI::App& app) {
  using mixing::CrossSectionRequest;
  static CrossSectionRequest request;
  auto* command = app.add_subcommand(
      "mix-calibrate",
      "Fit effective cross-section factors of the hapke mixing method's end-members to measured mixtures");
  add_request_options(command, request);
  // The command writes the calibration file it reports (Python may only return the factors).
  command->get_option("--output")->required();
  command->callback([] {
    run_request<CrossSectionRequest>([] {
      const mixing::CrossSectionRun run = mixing::run_cross_section_calibration(request);
      std::FILE* report = report_stream(request.output);
      fmt::print(report, "{}", run.table());
      fmt::print(report, "wrote {}\n", request.output);
    });
  });
}

}  // namespace roadbrdf::cli
