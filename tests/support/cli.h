// Test support: run the roadbrdf program built with the tests (tests/support/paths.h).
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

#include "support/paths.h"

namespace roadbrdf::test {

struct CliResult {
  int status;          // exit status
  std::string output;  // standard output and standard error together
};

inline CliResult run_cli(const std::string& arguments) {
  const std::string command = roadbrdf::test::cli_program() + " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  std::string output;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) output += buffer.data();
  const int status = pclose(pipe);
  return {WEXITSTATUS(status), output};
}

}  // namespace roadbrdf::test
