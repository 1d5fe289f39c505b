// Input files with every failure reported: "-" is standard input, a directory is "is a directory",
// and a read error is an error, never a silent end of file (which would truncate the data).
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace roadbrdf {

// How standard input and output are named in messages.
inline constexpr const char* kStandardInputName = "<standard input>";
inline constexpr const char* kStandardOutputName = "<standard output>";

// "-" names standard input (for inputs) or standard output (for outputs).
inline bool is_standard_stream(const std::string& path) { return path == "-"; }

// The name to show for a path in messages ("-" shown as <standard input>).
std::string input_display_name(const std::string& path);

class InputFile {
 public:
  // Opens `path` ("-" = standard input). Throws FileError ("cannot open file for reading: <reason>",
  // "is a directory").
  explicit InputFile(const std::string& path);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  // The next line without its '\n' (a '\r' before it is kept; callers trim); false at the end of the
  // file. Lines of any length are read in blocks (memory: the line itself). Throws FileError on a
  // read error, naming the line.
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
  bool fill();  // false at the end of the file
  std::string name_;
  std::FILE* file_ = nullptr;
  bool owned_ = false;
  std::vector<char> buffer_;
  std::size_t begin_ = 0, end_ = 0;
  long line_number_ = 0;
  std::uintmax_t size_hint_ = 0;
};

// The whole content of a file ("-" = standard input). Throws FileError.
std::string read_text_file(const std::string& path);

}  // namespace roadbrdf
