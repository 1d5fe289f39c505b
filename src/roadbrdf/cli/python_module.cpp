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
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  execv(interpreter.c_str(), argv.data());
  throw InputError("cannot run " + interpreter + " for " + purpose + " (set ROADBRDF_PYTHON to a Python 3 with " +
                   needs + ")");
}

}  // namespace roadbrdf::cli
