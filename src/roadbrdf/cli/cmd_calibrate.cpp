// roadbrdf calibrate SAMPLE.csv --reference REF.csv [--dark DARK.csv] --panel-reflectance RHO.txt
//                    [--panel-brf BRF.txt] -o DATA.csv
// roadbrdf calibrate --manifest RUN.csv --panel-reflectance RHO.txt -o DATA.csv
// f = (L_s - L_dark)/(L_ref - L_dark) * rho_ref(lambda)/pi (io/calibration.h). Made by the request
// contract (cli/request_options.h; the request's table is CalibrateRequest::fields,
// io/calibrate_request.cpp).
#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/request_options.h"
#include "roadbrdf/io/calibrate_request.h"

namespace roadbrdf::cli {

void register_calibrate_command(CLI::App& app) {
  static CalibrateRequest request;
  auto* command = app.add_subcommand(
      "calibrate", "BRDF from sample and reference-panel radiances: f = (L_s - L_dark)/(L_ref - L_dark) x rho_ref/pi");
  add_request_options(command, request);
  command->callback([] {
    run_request<CalibrateRequest>(
        [] { warn_missing_values(calibrate(with_standard_output(request)), request.output); });
  });
}

}  // namespace roadbrdf::cli
