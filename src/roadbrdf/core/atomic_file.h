// Output files: every write checked, never a half-written file, never a user's file replaced by
// accident.
//
// AtomicFile rules:
// - "-" is standard output: the stream is std::cout, commit() flushes it and checks for errors.
// - Symbolic links are written through: the file at the end of the chain is replaced, the links
//   are kept (a dangling link gets its target created).
// - A regular file (or a new one) is written to a temporary file in the target's folder, fsync'd,
//   given the replaced file's mode (and owner, where permitted), and renamed over the target. A
//   new file gets 0666 minus the umask, as the shell would create it. The temporary name is short
//   (".rbXXXXXX"), so it fits wherever the target's name fits. Hard links to the old file keep the
//   old content (rename replaces a name, not an inode).
// - Anything else that exists (FIFO, character or block device such as /dev/null, /dev/stdout on a
//   terminal or pipe) is opened and written directly: it is never renamed over or removed.
//   Directories and sockets are errors.
// - An existing file that may not be written (read-only) is an error, as a direct write would be.
// - The temporary file is removed on every error path (destructor without commit) and on SIGINT
//   and SIGTERM: live temporary files are kept in a small registry that an async-signal-safe
//   handler unlinks before the signal takes its default action. A handler installed earlier by
//   someone else (e.g. the Python interpreter) is called instead, and the process goes on.
// Every failure is a FileError naming the path and the system's reason.
#pragma once

#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace roadbrdf {

class AtomicFile {
 public:
  // Opens the output ("-" = standard output). Throws FileError.
  explicit AtomicFile(std::string path);
  ~AtomicFile();  // removes the temporary file if commit() was not called
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return *out_; }
  // Flush, fsync, close and rename into place; throws FileError naming the path on any failure
  // (e.g. "write failed: No space left on device").
  void commit();
  const std::string& path() const { return path_; }

 private:
  class Buffer;
  std::string path_;       // as given
  std::string target_;     // file finally replaced (symbolic links followed)
  std::string temporary_;  // "" when written directly
  int fd_ = -1;
  int slot_ = -1;  // registry slot of the temporary file (-1: none)
  std::unique_ptr<Buffer> buffer_;
  std::unique_ptr<std::ostream> own_stream_;
  std::ostream* out_ = nullptr;
  bool committed_ = false;
};

// Flush std::cout and stdout; throws FileError("<standard output>", "write failed: ...") when a
// write to standard output failed now or earlier (errors are sticky).
void flush_standard_output();

// A file a command reads or writes, with the option or argument that named it (for messages).
struct FileArgument {
  std::string role;  // e.g. "-o", "--residuals", "DATA"
  std::string path;
};

// Refuses, before any work is done, outputs that would destroy an input or each other: an output
// that is the same file as an input (after following links; hard links too), two outputs naming the
// same file, and standard input or standard output ("-") given twice. Empty paths are ignored.
// Non-regular outputs (e.g. /dev/null) may repeat. Throws InputError naming both arguments.
void check_distinct_files(const std::vector<FileArgument>& inputs, const std::vector<FileArgument>& outputs);

}  // namespace roadbrdf
