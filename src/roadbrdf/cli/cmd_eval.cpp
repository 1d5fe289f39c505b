// roadbrdf eval (MODEL -p NAME=VALUE ... | FIT.json | MIX.json [--fit NAME] [--wavelength NM])
//   (--theta-i D --phi-i D --theta-r D --phi-r D | --geometry FILE.csv)
// Made by the request contract (cli/request_options.h; the request's table is in io/eval_request.cpp).
#include <fmt/core.h>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/request_options.h"
#include "roadbrdf/io/eval_request.h"

namespace roadbrdf::cli {

void register_eval_command(CLI::App& app) {
  static EvalRequest request;
  auto* command =
      app.add_subcommand("eval", "Evaluate a model's BRDF [sr^-1] at one geometry or at every row of a file");
  add_request_options(command, request);
  refuse_fit_model_flag(command);
  command->callback([] {
    run_request<EvalRequest>([] {
      const EvalResult result = evaluate(request);
      AtomicFile out("-");
      if (!result.table) {
        out.stream() << fmt::format("{:.10g}\n", result.brdf.front());
      } else if (request.output.empty()) {
        write_eval_table(out.stream(), result);
      }
      out.commit();
    });
  });
}

}  // namespace roadbrdf::cli
