// roadbrdf study STUDY.json -o RESULTS.csv ...: design studies, run by the Python package's roadbrdf.studies
// module (local processes or a Dask cluster) with Debian's interpreter (override with $ROADBRDF_PYTHON), as
// `roadbrdf plot` does, so that the command line and roadbrdf.study(...) are one implementation.
#include <string>
#include <vector>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/python_module.h"

namespace roadbrdf::cli {

namespace {

void run_study(const std::vector<std::string>& arguments) {
  exec_python_module("roadbrdf.studies", arguments, "the study", "numpy");
}

}  // namespace

void register_study_command(CLI::App& app) {
  auto* command =
      app.add_subcommand("study",
                         "Design study: STUDY.json -o RESULTS.csv [--scheduler tcp://HOST:PORT] [--workers N] "
                         "(see `roadbrdf study --help`, docs/studies.md)");
  command->prefix_command();
  command->set_help_flag();  // --help goes to the Python module
  command->callback([command] {
    std::vector<std::string> remaining = command->remaining();
    if (remaining.empty()) remaining.push_back("--help");
    run_study(remaining);
  });
}

}  // namespace roadbrdf::cli
