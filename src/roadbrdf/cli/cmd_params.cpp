// roadbrdf params FIT.json [--wavelengths 600] [--model M ...] [--group-by COLS] [--format table|csv|markdown|latex]
//                 [-o OUT]
// The fitted parameters with standard errors and fit statistics, one row per fit and wavelength
// (fitting/params_table.h): the report's parameter tables, ready to paste. Made by the request contract
// (cli/request_options.h; the request's table is ParamsRequest::fields, fitting/params_table.cpp).
#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/request_options.h"
#include "roadbrdf/fitting/params_table.h"

namespace roadbrdf::cli {

void register_params_command(CLI::App& app) {
  static ParamsRequest request;
  auto* c = app.add_subcommand("params",
                               "Print the fitted parameters of a fit file with standard errors, RMSE, relative "
                               "errors, AIC/BIC and convergence: one row per fit (model, group) and wavelength");
  add_request_options(c, request);
  c->callback([] {
    run_request<ParamsRequest>([] {
      const ParamsTable table = read_params_table(request);
      for (const auto& note : table.notes) {
        fmt::print(stderr, "roadbrdf: note: {}\n", with_flags<ParamsRequest>(note));
      }
      write_params_output(request, table);
    });
  });
}

}  // namespace roadbrdf::cli
