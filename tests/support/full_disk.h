// Test support: two ways to make writes fail as on a full disk.
//  - /dev/full, where the machine has a real one (some containers give a /dev/full that accepts
//    writes, so its behaviour is probed, not assumed);
//  - a file-size limit (RLIMIT_FSIZE) with SIGXFSZ ignored: every write past the limit fails with
//    EFBIG ("File too large"). It works on every POSIX machine and on any target file, so the
//    tests that use it always run.
#pragma once

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <filesystem>
#include <string>

#include "support/cli.h"

namespace roadbrdf::test {

// True when writing to /dev/full fails with ENOSPC, as the Linux device does.
inline bool dev_full_refuses_writes() {
  const int fd = ::open("/dev/full", O_WRONLY);
  if (fd < 0) return false;
  const char byte = 'x';
  const bool refused = ::write(fd, &byte, 1) < 0 && errno == ENOSPC;
  ::close(fd);
  return refused;
}

inline constexpr const char* kNoFullDevice =
    "this machine's /dev/full accepts writes (or is missing); the file-size-limit tests cover full disks";

// The message a write past the file-size limit fails with.
inline constexpr const char* kFileTooLarge = "write failed: File too large";

// Runs the program with a file-size limit of 1 block of the shell's `ulimit -f` (512 bytes for dash,
// 1024 for bash; file_size_limit_bytes tells)
// and SIGXFSZ ignored (an ignored signal stays ignored across exec). Standard error (and standard
// output unless `stdout_target` is given) goes to the pipe, which the limit does not touch.
inline CliResult run_cli_with_file_size_limit(const std::string& arguments, const std::string& stdout_target = "") {
  const std::string redirect = stdout_target.empty() ? " 2>&1" : " 2>&1 >" + stdout_target;
  return run_shell("trap '' XFSZ; ulimit -f 1 && exec " + cli_program() + " " + arguments + redirect);
}

// The limit run_cli_with_file_size_limit sets, in bytes: the size a file written past it stops at.
inline std::uintmax_t file_size_limit_bytes(const std::string& scratch_file) {
  run_shell("trap '' XFSZ; ulimit -f 1 && head -c 100000 /dev/zero > " + scratch_file + " 2>/dev/null");
  const std::uintmax_t size = std::filesystem::file_size(scratch_file);
  std::filesystem::remove(scratch_file);
  return size;
}

}  // namespace roadbrdf::test
