// roadbrdf study STUDY.json -o RESULTS.csv ...: design studies, run by the Python package's roadbrdf.studies
// module (local processes or a Dask cluster) with Debian's interpreter (override with $ROADBRDF_PYTHON), as
// `roadbrdf plot` does, so that the command line and roadbrdf.study(...) are one implementation.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/core/data_path.h"
#include "roadbrdf/core/error.h"

namespace roadbrdf::cli {

namespace {

void run_study(const std::vector<std::string>& arguments) {
  std::string interpreter = "/usr/bin/python3";
  if (const char* env = std::getenv("ROADBRDF_PYTHON"); env != nullptr && *env != '\0') {
    interpreter = env;
  } else if (const auto beside = image_directory() / "python3"; std::filesystem::exists(beside)) {
    interpreter = beside.string();
  }
  std::string python_path = python_package_parent();
  if (const char* existing = std::getenv("PYTHONPATH"); existing && *existing) {
    python_path += python_path.empty() ? std::string(existing) : std::string(":") + existing;
  }
  if (!python_path.empty()) setenv("PYTHONPATH", python_path.c_str(), 1);
  std::vector<std::string> args = {interpreter, "-m", "roadbrdf.studies"};
  args.insert(args.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  execv(interpreter.c_str(), argv.data());
  throw InputError("cannot run " + interpreter + " for the study (set ROADBRDF_PYTHON to a Python 3 with numpy)");
}

}  // namespace

void register_study_command(CLI::App& app) {
  auto* command = app.add_subcommand(
      "study",
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
