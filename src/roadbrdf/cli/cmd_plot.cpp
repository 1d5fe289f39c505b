// roadbrdf plot KIND ... -o FILE.png|svg|pdf: figures, drawn by the Python package's
// roadbrdf.plot module (matplotlib) with Debian's interpreter (override with $ROADBRDF_PYTHON).
#include <unistd.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/core/error.h"

namespace roadbrdf::cli {

namespace {

void run(const std::vector<std::string>& arguments) {
  const char* interpreter_env = std::getenv("ROADBRDF_PYTHON");
  const std::string interpreter = interpreter_env && *interpreter_env ? interpreter_env : "/usr/bin/python3";
  std::string python_path = ROADBRDF_PYTHON_DIR;
  if (const char* existing = std::getenv("PYTHONPATH"); existing && *existing) python_path += std::string(":") + existing;
  setenv("PYTHONPATH", python_path.c_str(), 1);
  if (std::getenv("MPLBACKEND") == nullptr) setenv("MPLBACKEND", "Agg", 1);
  std::vector<std::string> args = {interpreter, "-m", "roadbrdf.plot"};
  args.insert(args.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  execv(interpreter.c_str(), argv.data());
  throw InputError("cannot run " + interpreter + " for the figures (set ROADBRDF_PYTHON to a Python 3 with numpy and "
                   "matplotlib)");
}

}  // namespace

void register_plot_command(CLI::App& app) {
  auto* command = app.add_subcommand(
      "plot",
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
