// Test support for adversarial command-line cases: a fresh folder holding the inputs of one case,
// and a record of every file in it, so that a test can assert that a refused command modified no
// input and left no temporary file behind.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli.h"
#include "support/scratch.h"

namespace roadbrdf::test {

class CaseFolder {
 public:
  explicit CaseFolder(const std::string& name) : dir_(scratch_path("case-" + name)) {
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  const std::string& dir() const { return dir_; }
  std::string path(const std::string& file) const { return dir_ + "/" + file; }
  std::string write(const std::string& file, const std::string& content) const {
    std::ofstream(path(file), std::ios::binary) << content;
    return path(file);
  }
  std::string copy(const std::string& source, const std::string& file) const {
    std::filesystem::copy_file(source, path(file), std::filesystem::copy_options::overwrite_existing);
    return path(file);
  }
  // Remember every name in the folder with its content (symbolic links by their target).
  void snapshot() { before_ = contents(); }
  // Names added, removed or changed since snapshot(), e.g. {"+ .rbX1y2Z3", "~ data.csv"}.
  std::vector<std::string> changes() const {
    const auto now = contents();
    std::vector<std::string> out;
    for (const auto& [name, content] : before_) {
      const auto it = now.find(name);
      if (it == now.end())
        out.push_back("- " + name);
      else if (it->second != content)
        out.push_back("~ " + name);
    }
    for (const auto& [name, content] : now) {
      if (!before_.count(name)) out.push_back("+ " + name);
    }
    return out;
  }

 private:
  std::map<std::string, std::string> contents() const {
    namespace fs = std::filesystem;
    std::map<std::string, std::string> m;
    for (const auto& e : fs::recursive_directory_iterator(dir_)) {
      const std::string name = fs::relative(e.path(), dir_).string();
      if (e.is_symlink()) {
        m[name] = "-> " + fs::read_symlink(e.path()).string();
      } else if (e.is_regular_file()) {
        std::ifstream in(e.path(), std::ios::binary);
        std::stringstream s;
        s << in.rdbuf();
        m[name] = s.str();
      } else {
        m[name] = "(not a regular file)";
      }
    }
    return m;
  }
  std::string dir_;
  std::map<std::string, std::string> before_;
};

// The message of a refused command: non-zero exit that is not an internal error (3) or a crash
// (>= 128), and every fragment present.
inline ::testing::AssertionResult refused_with(const CliResult& r, const std::vector<std::string>& fragments) {
  if (r.status == 0 || r.status == 3 || r.status >= 128) {
    return ::testing::AssertionFailure() << "exit status " << r.status << ", output:\n" << r.output;
  }
  for (const auto& f : fragments) {
    if (r.output.find(f) == std::string::npos) {
      return ::testing::AssertionFailure() << "no '" << f << "' in:\n" << r.output;
    }
  }
  return ::testing::AssertionSuccess();
}

}  // namespace roadbrdf::test
