// Sub-commands of the roadbrdf program; one file each (cmd_*.cpp).
#pragma once

#include <CLI/CLI.hpp>

namespace roadbrdf::cli {

void register_models_command(CLI::App& app);
void register_eval_command(CLI::App& app);
// [command-declarations]

}  // namespace roadbrdf::cli
