// Messages for command lines that CLI11 cannot parse: "roadbrdf: error: ..." naming the unknown
// command or option and the nearest valid name (core/nearest_name.h).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace roadbrdf::cli {

// The message for a parse error of `argv` (without "roadbrdf: error: ").
std::string explain_parse_error(CLI::App& app, int argc, char** argv, const CLI::ParseError& error);

}  // namespace roadbrdf::cli
