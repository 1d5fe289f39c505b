// Input files with every failure reported: "-" is standard input, a directory is "is a directory",
// and a read error is an error, never a silent end of file (which would truncate the data).
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

namespace roadbrdf {

// How standard input and output are named in messages.
inline constexpr const char* kStandardInputName = "<standard input>";
inline constexpr const char* kStandardOutputName = "<standard output>";

// "-" names standard input (for inputs) or standard output (for outputs).
inline bool is_standard_stream(const std::string& path) { return path == "-"; }

// The name to show for a path in messages ("-" shown as <standard input>).
std::string input_display_name(const std::string& path);

// What a format allows an input to be, so that an endless or huge input (a device such as
// /dev/zero, a sparse file, a FIFO nobody writes to) is refused with a message instead of filling
// the memory or waiting forever.
struct InputLimits {
  // The format, for messages ("an .asd file", "a run manifest").
  std::string what = "an input file";
  // The most bytes the file may hold: a regular file's size is checked before it is read, any other
  // input (standard input, pipes, devices) as it is read.
  std::uintmax_t max_bytes = std::uintmax_t{4} << 30;
  // The longest line read_line returns (the line-reading formats; read_all is bound by max_bytes).
  std::size_t max_line_bytes = std::size_t{64} << 20;
  // Refuse anything but a regular file (a FIFO, a device, a socket) when the file is named inside
  // another file or must be read whole and reliably; standard input ("-") stays allowed.
  bool regular_file_only = false;
};

// Byte counts for messages: "3221225472 bytes (3 GiB)".
std::string byte_count_text(std::uintmax_t bytes);

class InputFile {
 public:
  // Opens `path` ("-" = standard input). Throws FileError ("cannot open file for reading: <reason>",
  // "is a directory", a non-regular file where `limits` want a regular one, a file beyond
  // limits.max_bytes). Opening never waits for a FIFO's writer unless a FIFO is allowed.
  explicit InputFile(const std::string& path, const InputLimits& limits = {});
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  // The next line without its '\n' (a '\r' before it is kept; callers trim); false at the end of the
  // file. Lines of any length are read in blocks (memory: a block, or the longest line). Throws
  // FileError on a read error, naming the line. The view points into the reader's buffer and is
  // valid until the next read: a line is never copied (a wide CSV row is tens of kB).
  bool read_line(std::string_view& line);
  // The same, copied into `line`.
  bool read_line(std::string& line);
  // Everything not read yet. Throws FileError on a read error.
  std::string read_all();

  // The name for messages ("<standard input>" for "-").
  const std::string& name() const { return name_; }
  // Lines returned so far.
  long line_number() const { return line_number_; }
  // Size of a regular file in bytes; 0 when unknown (standard input, pipes).
  std::uintmax_t size_hint() const { return size_hint_; }

 private:
  // Reads more of the file after the unread bytes (moved to the front of the buffer first, which
  // grows when one line fills it); false at the end of the file. Throws FileError past
  // limits_.max_bytes.
  bool fill();
  void open(const std::string& path);
  std::string name_;
  InputLimits limits_;
  std::uintmax_t bytes_read_ = 0;
  std::FILE* file_ = nullptr;
  bool owned_ = false;
  std::vector<char> buffer_;
  std::size_t begin_ = 0, end_ = 0;  // the unread bytes of buffer_
  std::size_t scanned_ = 0;          // how far from begin_ there is no newline
  long line_number_ = 0;
  std::uintmax_t size_hint_ = 0;
};

// The whole content of a file ("-" = standard input). Throws FileError.
std::string read_text_file(const std::string& path, const InputLimits& limits = {});

}  // namespace roadbrdf
