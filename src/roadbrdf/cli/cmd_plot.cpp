// roadbrdf plot KIND ... -o FILE.png|svg|pdf: figures, drawn by the Python package's
// roadbrdf.plot module (matplotlib) with Debian's interpreter (override with $ROADBRDF_PYTHON).
#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/python_module.h"

namespace roadbrdf::cli {

void register_plot_command(CLI::App& app) {
  add_python_command(app,
                     PythonCommand{"plot",
                                   "Figures: plot spectral|hemisphere|plane|fit|albedo|rtable ... -o FILE.png|svg|pdf "
                                   "(see `roadbrdf plot --help` / `roadbrdf plot KIND --help`)",
                                   "roadbrdf.plot", "the figures", "numpy and matplotlib", true});
}

}  // namespace roadbrdf::cli
