#include "roadbrdf/cli/python_module.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include "roadbrdf/core/data_path.h"
#include "roadbrdf/core/error.h"

namespace roadbrdf::cli {

void exec_python_module(const std::string& module, const std::vector<std::string>& arguments,
                        const std::string& purpose, const std::string& needs) {
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
  std::vector<std::string> args = {interpreter, "-m", module};
  args.insert(args.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  execv(interpreter.c_str(), argv.data());
  throw InputError("cannot run " + interpreter + " for " + purpose + " (set ROADBRDF_PYTHON to a Python 3 with " +
                   needs + ")");
}

void add_python_command(CLI::App& app, const PythonCommand& command) {
  auto* sub = app.add_subcommand(command.name, command.help);
  sub->prefix_command();
  sub->set_help_flag();  // --help goes to the Python module
  sub->callback([sub, command] {
    std::vector<std::string> remaining = sub->remaining();
    if (remaining.empty()) remaining.emplace_back("--help");
    if (command.draws && std::getenv("MPLBACKEND") == nullptr) setenv("MPLBACKEND", "Agg", 1);
    exec_python_module(command.module, remaining, command.purpose, command.needs);
  });
}

}  // namespace roadbrdf::cli
