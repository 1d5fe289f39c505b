#include "roadbrdf/core/input_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include "roadbrdf/core/error.h"

namespace roadbrdf {

namespace {
constexpr std::size_t kBlock = 1 << 16;
}  // namespace

std::string input_display_name(const std::string& path) {
  return is_standard_stream(path) ? std::string(kStandardInputName) : path;
}

InputFile::InputFile(const std::string& path) : name_(input_display_name(path)) {
  if (path.empty()) throw InputError("an input file name is empty");
  if (is_standard_stream(path)) {
    file_ = stdin;
  } else {
    file_ = std::fopen(path.c_str(), "rb");
    if (!file_) throw FileError(name_, 0, 0, std::string("cannot open file for reading: ") + std::strerror(errno));
    owned_ = true;
  }
  struct stat st {};
  if (::fstat(::fileno(file_), &st) == 0) {
    if (S_ISDIR(st.st_mode)) {
      if (owned_) std::fclose(file_);
      file_ = nullptr;
      throw FileError(name_, 0, 0, "is a directory, not a file");
    }
    if (S_ISREG(st.st_mode)) size_hint_ = static_cast<std::uintmax_t>(st.st_size);
  }
  buffer_.resize(kBlock);
}

InputFile::~InputFile() {
  if (owned_ && file_) std::fclose(file_);
}

bool InputFile::fill() {
  begin_ = 0;
  end_ = std::fread(buffer_.data(), 1, buffer_.size(), file_);
  if (end_ > 0) return true;
  if (std::ferror(file_)) {
    const int error = errno;
    throw FileError(name_, line_number_ + 1, 0,
                    std::string("read error: ") + (error ? std::strerror(error) : "unknown I/O error"));
  }
  return false;
}

bool InputFile::read_line(std::string& line) {
  line.clear();
  bool any = false;
  while (true) {
    if (begin_ == end_ && !fill()) {
      if (any) ++line_number_;
      return any;
    }
    any = true;
    const char* start = buffer_.data() + begin_;
    const auto* newline = static_cast<const char*>(std::memchr(start, '\n', end_ - begin_));
    if (newline) {
      line.append(start, static_cast<std::size_t>(newline - start));
      begin_ += static_cast<std::size_t>(newline - start) + 1;
      ++line_number_;
      return true;
    }
    line.append(start, end_ - begin_);
    begin_ = end_;
  }
}

std::string InputFile::read_all() {
  std::string text(buffer_.data() + begin_, end_ - begin_);
  begin_ = end_;
  if (size_hint_ > text.size()) text.reserve(static_cast<std::size_t>(size_hint_));
  while (fill()) {
    text.append(buffer_.data(), end_);
    begin_ = end_;
  }
  return text;
}

std::string read_text_file(const std::string& path) {
  InputFile in(path);
  return in.read_all();
}

}  // namespace roadbrdf
