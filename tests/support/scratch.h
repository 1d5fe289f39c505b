// Test support: a scratch directory of this test process for temporary files.
// ctest runs the tests of one program as parallel processes (and two checkouts may be tested at
// once), so fixed names directly in the temporary directory collide; every process gets its own
// directory, removed when the process ends.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace roadbrdf::test {

class ScratchDirectory {
 public:
  ScratchDirectory() : path_(std::filesystem::temp_directory_path() / ("roadbrdf-test-" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path_);
  }
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// The path of `name` in this process's scratch directory.
inline std::string scratch_path(const std::string& name) {
  static const ScratchDirectory directory;
  return (directory.path() / name).string();
}

}  // namespace roadbrdf::test
