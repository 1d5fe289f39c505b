// Output files written so that a crash never leaves a half-written file.
#pragma once

#include <fstream>
#include <string>

namespace roadbrdf {

// Write a file atomically: the content goes to a temporary file in the same directory, which is
// renamed over `path` only once complete, so a crash never leaves a half-written file.
class AtomicFile {
 public:
  explicit AtomicFile(std::string path);
  ~AtomicFile();  // removes the temporary file if commit() was not called
  std::ofstream& stream() { return out_; }
  void commit();  // flush, close, rename; throws InputError on failure

 private:
  std::string path_;
  std::string temporary_;
  std::ofstream out_;
  bool committed_ = false;
};

}  // namespace roadbrdf
