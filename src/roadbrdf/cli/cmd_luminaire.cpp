// roadbrdf luminaire FILE [--json]: the summary of a luminaire photometry file (EULUMDAT or IES
// LM-63): name, flux, maximum intensity and its direction, DLOR, ULOR, symmetry
// (lighting/luminaire_request.h). Made by the request contract (cli/request_options.h).
#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/request_options.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/lighting/luminaire_request.h"

namespace roadbrdf::cli {

void register_luminaire_command(CLI::App& app) {
  static lighting::LuminaireRequest request;
  static bool as_json = false;
  auto* command = app.add_subcommand("luminaire",
                                     "Summary of a luminaire photometry file (EULUMDAT .ldt, IES LM-63 .ies): name, "
                                     "flux, maximum intensity and its direction, DLOR, ULOR, symmetry");
  add_request_options(command, request);
  command->add_flag("--json", as_json, "Machine-readable output: every figure, the metadata and the principal planes");
  command->callback([] {
    run_request<lighting::LuminaireRequest>([] {
      const lighting::LuminaireSummary result = lighting::luminaire_summary(request);
      print_diagnostics<lighting::LuminaireRequest>(result.diagnostics);
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
