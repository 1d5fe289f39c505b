// roadbrdf lighting INSTALLATION.json [--surface S] [--class M3] [--operating-hours H] [--map MAP.csv] [--json]:
// the EN 13201-3 calculation of a road-lighting installation, its M class, energy indicators, least
// flux for a class and upward light (lighting/lighting_request.h). Made by the request contract
// (cli/request_options.h).
#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/request_options.h"
#include "roadbrdf/lighting/lighting_request.h"

namespace roadbrdf::cli {

void register_lighting_command(CLI::App& app) {
  add_request_command<lighting::LightingRequest>(
      app, "lighting",
      "EN 13201 road-lighting calculation of an installation file: L_av, U_o, U_l, f_TI, R_EI, E_av, the M class, "
      "D_P, D_E, least flux for a class, upward light",
      "Machine-readable output: every figure, per lane, and the grid",
      [](const lighting::LightingRequest& request) { return lighting::lighting(request); });
}

}  // namespace roadbrdf::cli
