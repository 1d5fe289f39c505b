// roadbrdf simulate MODEL_OR_FIT --grid GRID.csv --wavelengths A:B:STEP [--spectral NAME=FILE] [--noise ...]
//                   [--seed S] -o DATA.csv
// Virtual gonioreflectometer (io/simulate.h). Made by the request contract (cli/request_options.h; the
// request's table is in io/simulate_request.cpp).
#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/request_options.h"
#include "roadbrdf/io/simulate_request.h"

namespace roadbrdf::cli {

void register_simulate_command(CLI::App& app) {
  static SimulateRequest request;
  auto* command = app.add_subcommand(
      "simulate", "Virtual gonioreflectometer: sample a model or a fit on an instrument grid, with reproducible noise");
  add_request_options(command, request);
  refuse_fit_model_flag(command);
  command->callback([] {
    run_request<SimulateRequest>([] { warn_missing_values(simulate(with_standard_output(request)), request.output); });
  });
}

}  // namespace roadbrdf::cli
