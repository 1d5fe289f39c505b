// roadbrdf luminaire FILE [--json]: the summary of a luminaire photometry file (EULUMDAT or IES
// LM-63): name, flux, maximum intensity and its direction, DLOR, ULOR, symmetry
// (lighting/luminaire_request.h). Made by the request contract (cli/request_options.h).
#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/request_options.h"
#include "roadbrdf/lighting/luminaire_request.h"

namespace roadbrdf::cli {

void register_luminaire_command(CLI::App& app) {
  add_request_command<lighting::LuminaireRequest>(
      app, "luminaire",
      "Summary of a luminaire photometry file (EULUMDAT .ldt, IES LM-63 .ies): name, flux, maximum intensity and "
      "its direction, DLOR, ULOR, symmetry",
      "Machine-readable output: every figure, the metadata and the principal planes",
      [](const lighting::LuminaireRequest& request) { return lighting::luminaire_summary(request); });
}

}  // namespace roadbrdf::cli
