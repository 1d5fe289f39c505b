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

// Runs a shell command line; returns its exit status and everything it printed to the pipe.
inline CliResult run_shell(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  std::string output;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) output += buffer.data();
  const int status = pclose(pipe);
  // A program killed by a signal counts as 128 + the signal, as the shell reports it.
  return {WIFSIGNALED(status) ? 128 + WTERMSIG(status) : WEXITSTATUS(status), output};
}

inline CliResult run_cli(const std::string& arguments) {
  return run_shell(roadbrdf::test::cli_program() + " " + arguments + " 2>&1");
}

// The program with its standard output sent to `target` (e.g. /dev/full); `output` holds standard
// error only.
inline CliResult run_cli_with_stdout(const std::string& arguments, const std::string& target) {
  return run_shell(roadbrdf::test::cli_program() + " " + arguments + " 2>&1 >" + target);
}

}  // namespace roadbrdf::test
