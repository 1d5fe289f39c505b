// roadbrdf plot KIND ... -o FILE.png|svg|pdf: figures, drawn by the Python package's
// roadbrdf.plot module (matplotlib) with Debian's interpreter (override with $ROADBRDF_PYTHON).
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

void run(const std::vector<std::string>& arguments) {
  // The interpreter: $ROADBRDF_PYTHON, else the python3 next to the program (a virtual environment
  // that pip installed roadbrdf into), else Debian's.
  std::string interpreter = "/usr/bin/python3";
  if (const char* env = std::getenv("ROADBRDF_PYTHON"); env != nullptr && *env != '\0') {
    interpreter = env;
  } else if (const auto beside = image_directory() / "python3"; std::filesystem::exists(beside)) {
    interpreter = beside.string();
  }
  // The package that belongs to this program goes first on the path (data_path.h); when there is
  // none (installed by pip) the interpreter's own path has it.
  std::string python_path = python_package_parent();
  if (const char* existing = std::getenv("PYTHONPATH"); existing && *existing) {
    python_path += python_path.empty() ? std::string(existing) : std::string(":") + existing;
  }
  if (!python_path.empty()) setenv("PYTHONPATH", python_path.c_str(), 1);
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
