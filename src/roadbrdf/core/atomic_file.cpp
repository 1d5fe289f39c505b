#include "roadbrdf/core/atomic_file.h"

#include <filesystem>
#include <random>

#include "roadbrdf/core/error.h"

namespace roadbrdf {

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  std::random_device rd;
  temporary_ = path_ + ".tmp" + std::to_string(rd() % 1000000);
  out_.open(temporary_, std::ios::out | std::ios::trunc);
  if (!out_) throw FileError(path_, 0, 0, "cannot open file for writing");
  out_.precision(17);
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    out_.close();
    std::error_code ec;
    std::filesystem::remove(temporary_, ec);
  }
}

void AtomicFile::commit() {
  out_.flush();
  if (!out_) throw FileError(path_, 0, 0, "write failed");
  out_.close();
  std::error_code ec;
  std::filesystem::rename(temporary_, path_, ec);
  if (ec) throw FileError(path_, 0, 0, "cannot rename temporary file into place: " + ec.message());
  committed_ = true;
}

}  // namespace roadbrdf
