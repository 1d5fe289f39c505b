// roadbrdf study STUDY.json -o RESULTS.csv ...: design studies, run by the Python package's roadbrdf.studies
// module (local processes or a Dask cluster) with Debian's interpreter (override with $ROADBRDF_PYTHON), as
// `roadbrdf plot` does, so that the command line and roadbrdf.study(...) are one implementation.
#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/python_module.h"

namespace roadbrdf::cli {

void register_study_command(CLI::App& app) {
  add_python_command(
      app, PythonCommand{"study",
                         "Design study: STUDY.json -o RESULTS.csv [--scheduler tcp://HOST:PORT] [--workers N] "
                         "(see `roadbrdf study --help`, docs/studies.md)",
                         "roadbrdf.studies", "the study", "numpy", false});
}

}  // namespace roadbrdf::cli
