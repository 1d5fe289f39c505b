// Commands implemented by the Python package (plot, study) hand over to it here, so that the
// command line and the Python function are one implementation.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace roadbrdf::cli {

// What a command made by the Python package needs: its name and help line here, the module that
// runs it, what it is for and which packages it needs (for the error when they are missing), and
// whether it draws with matplotlib (then MPLBACKEND defaults to Agg: no display needed).
struct PythonCommand {
  std::string name, help, module, purpose, needs;
  bool draws = false;
};

// Registers the command: every argument (and --help) goes to `python -m MODULE`; no argument is
// `--help`.
void add_python_command(CLI::App& app, const PythonCommand& command);

// Replaces this process by `python -m MODULE ARGUMENTS...`. The interpreter: $ROADBRDF_PYTHON,
// else the python3 next to the program (a virtual environment that pip installed roadbrdf into),
// else Debian's /usr/bin/python3. The package that belongs to this program goes first on
// PYTHONPATH (core/data_path.h); when there is none (installed by pip) the interpreter's own path
// has it. Returns only by throwing InputError, whose message names `needs` (e.g. "numpy").
[[noreturn]] void exec_python_module(const std::string& module, const std::vector<std::string>& arguments,
                                     const std::string& purpose, const std::string& needs);

}  // namespace roadbrdf::cli
