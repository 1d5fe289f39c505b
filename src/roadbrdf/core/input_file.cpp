#include "roadbrdf/core/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iterator>

#include "roadbrdf/core/error.h"

namespace roadbrdf {

namespace {
constexpr std::size_t kBlock = 1 << 16;
}  // namespace

std::string input_display_name(const std::string& path) {
  return is_standard_stream(path) ? std::string(kStandardInputName) : path;
}

std::string byte_count_text(std::uintmax_t bytes) {
  constexpr const char* kUnits[] = {"KiB", "MiB", "GiB", "TiB"};
  std::string text = std::to_string(bytes) + " bytes";
  if (bytes < 1024) return text;
  double value = static_cast<double>(bytes);
  std::size_t unit = 0;
  for (value /= 1024; value >= 1024 && unit + 1 < std::size(kUnits); value /= 1024) ++unit;
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, " (%.3g %s)", value, kUnits[unit]);
  return text + buffer;
}

namespace {

const char* file_kind(mode_t mode) {
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

}  // namespace

InputFile::InputFile(const std::string& path, const InputLimits& limits)
    : name_(input_display_name(path)), limits_(limits) {
  if (path.empty()) throw InputError("an input file name is empty");
  if (is_standard_stream(path)) {
    file_ = stdin;
  } else {
    open(path);
  }
  struct stat st {};
  if (::fstat(::fileno(file_), &st) == 0 && S_ISREG(st.st_mode)) {
    size_hint_ = static_cast<std::uintmax_t>(st.st_size);
    if (size_hint_ > limits_.max_bytes) {
      if (owned_) std::fclose(file_);
      file_ = nullptr;
      throw FileError(name_, 0, 0,
                      "file is " + byte_count_text(size_hint_) + ", more than the " +
                          byte_count_text(limits_.max_bytes) + " " + limits_.what + " may hold");
    }
  }
  buffer_.resize(kBlock);
}

// Opened without blocking (a FIFO without a writer would block the open), then checked: a directory,
// or a non-regular file where the format wants a regular one, is refused before any read. A FIFO
// that is allowed is opened again, blocking as usual until its writer comes.
void InputFile::open(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw FileError(name_, 0, 0, std::string("cannot open file for reading: ") + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int error = errno;
    ::close(fd);
    throw FileError(name_, 0, 0, std::string("cannot open file for reading: ") + std::strerror(error));
  }
  if (S_ISDIR(st.st_mode)) {
    ::close(fd);
    throw FileError(name_, 0, 0, "is a directory, not a file");
  }
  if (!S_ISREG(st.st_mode) && limits_.regular_file_only) {
    ::close(fd);
    throw FileError(name_, 0, 0,
                    std::string("is ") + file_kind(st.st_mode) + ", not a regular file: " + limits_.what +
                        " must be a regular file");
  }
  if (S_ISFIFO(st.st_mode)) {
    ::close(fd);
    file_ = std::fopen(path.c_str(), "rb");
    if (!file_) throw FileError(name_, 0, 0, std::string("cannot open file for reading: ") + std::strerror(errno));
    owned_ = true;
    return;
  }
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags < 0 || ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) != 0 || !(file_ = ::fdopen(fd, "rb"))) {
    const int error = errno;
    ::close(fd);
    throw FileError(name_, 0, 0, std::string("cannot open file for reading: ") + std::strerror(error));
  }
  owned_ = true;
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
  bytes_read_ += n;
  if (bytes_read_ > limits_.max_bytes) {
    throw FileError(name_, line_number_ + 1, 0,
                    "more than the " + byte_count_text(limits_.max_bytes) + " " + limits_.what +
                        " may hold: not such a file, or an endless input");
  }
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
    if (unread > limits_.max_line_bytes) {
      throw FileError(name_, line_number_ + 1, 0,
                      "line longer than " + byte_count_text(limits_.max_line_bytes) + " without a line end: not " +
                          limits_.what + ", or an endless input");
    }
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

std::string read_text_file(const std::string& path, const InputLimits& limits) {
  InputFile in(path, limits);
  return in.read_all();
}

}  // namespace roadbrdf
