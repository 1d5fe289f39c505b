// roadbrdf lighting INSTALLATION.json [--surface S] [--class M3] [--operating-hours H] [--map MAP.csv] [--json]:
// the EN 13201-3 calculation of a road-lighting installation, its M class, energy indicators, least
// flux for a class and upward light (lighting/lighting_request.h). Made by the request contract
// (cli/request_options.h).
#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/request_options.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/lighting/lighting_request.h"

namespace roadbrdf::cli {

void register_lighting_command(CLI::App& app) {
  static lighting::LightingRequest request;
  static bool as_json = false;
  auto* command = app.add_subcommand("lighting",
                                     "EN 13201 road-lighting calculation of an installation file: L_av, U_o, U_l, "
                                     "f_TI, R_EI, E_av, the M class, D_P, D_E, least flux for a class, upward light");
  add_request_options(command, request);
  command->add_flag("--json", as_json, "Machine-readable output: every figure, per lane, and the grid");
  command->callback([] {
    run_request<lighting::LightingRequest>([] {
      const lighting::LightingResult result = lighting::lighting(request);
      print_diagnostics<lighting::LightingRequest>(result.diagnostics);
      AtomicFile out("-");
      if (as_json) {
        write_json(out.stream(), result.to_json(), 2);
        out.stream() << '\n';
      } else {
        out.stream() << result.summary_text();
      }
      out.commit();
    });
  });
}

}  // namespace roadbrdf::cli
