// roadbrdf lighting INSTALLATION.json [--surface S] [--class M3] [--operating-hours H] [--map MAP.csv] [--json]:
// the EN 13201-3 calculation of a road-lighting installation, its M class, energy indicators, least
// flux for a class and upward light (lighting/lighting_request.h). Made by the request contract
// (cli/request_options.h).
#include <optional>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/request_options.h"
#include "roadbrdf/core/elapsed_ticker.h"
#include "roadbrdf/lighting/lighting_request.h"

namespace roadbrdf::cli {

void register_lighting_command(CLI::App& app) {
  add_request_command<lighting::LightingRequest>(
      app, "lighting",
      "EN 13201 road-lighting calculation of an installation file: L_av, U_o, U_l, f_TI, R_EI, E_av, the M class, "
      "D_P, D_E, least flux for a class, upward light",
      "Machine-readable output: every figure, per lane, and the grid", [](const lighting::LightingRequest& request) {
        // A pavement given as a fit file (its r-table computed first) or a fine grid takes seconds: the
        // elapsed time is shown, a bar from 2 s on a terminal, a line every 10 s in a log.
        ProgressBar bar("lighting", stderr, ProgressBar::stderr_style(false), {}, 2.0);
        std::optional<ElapsedTicker> ticker(std::in_place, bar);
        auto result = lighting::lighting(request);
        ticker.reset();
        bar.update(1, 1);
        bar.finish();
        return result;
      });
}

}  // namespace roadbrdf::cli
