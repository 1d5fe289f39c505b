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
  if (begin_ > 0) {
    std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
    end_ -= begin_;
    begin_ = 0;
  }
  if (end_ == buffer_.size()) buffer_.resize(2 * buffer_.size());
  const std::size_t n = std::fread(buffer_.data() + end_, 1, buffer_.size() - end_, file_);
  end_ += n;
  if (n > 0) return true;
  if (std::ferror(file_)) {
    const int error = errno;
    throw FileError(name_, line_number_ + 1, 0,
                    std::string("read error: ") + (error ? std::strerror(error) : "unknown I/O error"));
  }
  return false;
}

bool InputFile::read_line(std::string_view& line) {
  while (true) {
    const char* start = buffer_.data() + begin_;
    const std::size_t unread = end_ - begin_;
    const auto* newline = static_cast<const char*>(std::memchr(start + scanned_, '\n', unread - scanned_));
    if (newline) {
      const auto length = static_cast<std::size_t>(newline - start);
      line = std::string_view(start, length);
      begin_ += length + 1;
      scanned_ = 0;
      ++line_number_;
      return true;
    }
    scanned_ = unread;
    if (!fill()) {
      if (unread == 0) return false;
      // The last line, without a final newline.
      line = std::string_view(buffer_.data() + begin_, unread);
      begin_ = end_;
      scanned_ = 0;
      ++line_number_;
      return true;
    }
  }
}

bool InputFile::read_line(std::string& line) {
  std::string_view view;
  if (!read_line(view)) {
    line.clear();
    return false;
  }
  line.assign(view);
  return true;
}

std::string InputFile::read_all() {
  std::string text(buffer_.data() + begin_, end_ - begin_);
  begin_ = end_ = scanned_ = 0;
  if (size_hint_ > text.size()) text.reserve(static_cast<std::size_t>(size_hint_));
  while (fill()) {
    text.append(buffer_.data(), end_);
    begin_ = end_ = 0;
  }
  return text;
}

std::string read_text_file(const std::string& path) {
  InputFile in(path);
  return in.read_all();
}

}  // namespace roadbrdf
