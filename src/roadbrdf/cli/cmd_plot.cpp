// roadbrdf plot KIND ... -o FILE.png|svg|pdf: figures, drawn by the Python package's
// roadbrdf.plot module (matplotlib) with Debian's interpreter (override with $ROADBRDF_PYTHON).
#include <cstdlib>
#include <string>
#include <vector>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/python_module.h"

namespace roadbrdf::cli {

namespace {

void run(const std::vector<std::string>& arguments) {
  if (std::getenv("MPLBACKEND") == nullptr) setenv("MPLBACKEND", "Agg", 1);
  exec_python_module("roadbrdf.plot", arguments, "the figures", "numpy and matplotlib");
}

}  // namespace

void register_plot_command(CLI::App& app) {
  auto* command =
      app.add_subcommand("plot",
                         "Figures: plot spectral|hemisphere|plane|fit|albedo|rtable ... -o FILE.png|svg|pdf "
                         "(see `roadbrdf plot --help` / `roadbrdf plot KIND --help`)");
  command->prefix_command();
  command->set_help_flag();  // --help goes to the Python module
  command->callback([command] {
    std::vector<std::string> remaining = command->remaining();
    if (remaining.empty()) remaining.push_back("--help");
    run(remaining);
  });
}

}  // namespace roadbrdf::cli
