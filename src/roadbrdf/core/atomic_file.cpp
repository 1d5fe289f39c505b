#include "roadbrdf/core/atomic_file.h"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <random>
#include <streambuf>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/input_file.h"
#include "roadbrdf/core/random.h"

namespace roadbrdf {

namespace fs = std::filesystem;

// ---- registry of live temporary files, emptied by SIGINT / SIGTERM ---------------------------------
//
// A fixed array (no allocation, no locks) that the signal handler can walk: a slot is free (0),
// being filled (1) or holds the path of a live temporary file (2). Creating a temporary file and
// publishing it, and renaming it and releasing the slot, happen with both signals blocked, so the
// handler never sees a file that exists but is not registered.

namespace {

constexpr int kSlots = 64;
constexpr std::size_t kSlotPath = 4096;

struct Slot {
  std::atomic<int> state{0};
  // Zero-initialised, so that the registry is constant-initialised: no page of it is touched at
  // start-up (a dynamic initialiser would fault in all 64 slots of every command).
  char path[kSlotPath]{};
};

Slot g_slots[kSlots];
struct sigaction g_previous_int {};
struct sigaction g_previous_term {};
std::once_flag g_install_once;

extern "C" void remove_temporaries_and_reraise(int signal_number, siginfo_t* info, void* context) {
  const struct sigaction& previous = signal_number == SIGINT ? g_previous_int : g_previous_term;
  // Someone else handles this signal (e.g. the Python interpreter turns SIGINT into
  // KeyboardInterrupt): the process goes on, the destructors clean up.
  if ((previous.sa_flags & SA_SIGINFO) != 0) {
    if (previous.sa_sigaction) previous.sa_sigaction(signal_number, info, context);
    return;
  }
  if (previous.sa_handler != SIG_DFL && previous.sa_handler != SIG_IGN) {
    previous.sa_handler(signal_number);
    return;
  }
  // The default action ends the process: remove the temporary files, then let it happen.
  for (Slot& slot : g_slots) {
    if (slot.state.load(std::memory_order_acquire) == 2) ::unlink(slot.path);
  }
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  sigemptyset(&default_action.sa_mask);
  ::sigaction(signal_number, &default_action, nullptr);
  ::raise(signal_number);  // delivered when this handler returns
}

void install_handlers() {
  for (int signal_number : {SIGINT, SIGTERM}) {
    struct sigaction& previous = signal_number == SIGINT ? g_previous_int : g_previous_term;
    if (::sigaction(signal_number, nullptr, &previous) != 0) continue;
    if ((previous.sa_flags & SA_SIGINFO) == 0 && previous.sa_handler == SIG_IGN) continue;  // stays ignored
    struct sigaction action {};
    action.sa_sigaction = remove_temporaries_and_reraise;
    action.sa_flags = SA_SIGINFO | SA_RESTART;
    sigemptyset(&action.sa_mask);
    ::sigaction(signal_number, &action, nullptr);
  }
}

// Blocks SIGINT and SIGTERM in this thread for its lifetime.
class SignalBlock {
 public:
  SignalBlock() {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    ::pthread_sigmask(SIG_BLOCK, &set, &old_);
  }
  ~SignalBlock() { ::pthread_sigmask(SIG_SETMASK, &old_, nullptr); }

 private:
  sigset_t old_;
};

int acquire_slot(const std::string& path) {
  if (path.size() >= kSlotPath) return -1;
  for (int k = 0; k < kSlots; ++k) {
    int expected = 0;
    if (g_slots[k].state.compare_exchange_strong(expected, 1, std::memory_order_acq_rel)) {
      std::memcpy(g_slots[k].path, path.c_str(), path.size() + 1);
      g_slots[k].state.store(2, std::memory_order_release);
      return k;
    }
  }
  return -1;  // full: the file is still removed by the destructor, only not on a signal
}

void release_slot(int slot) {
  if (slot >= 0) g_slots[slot].state.store(0, std::memory_order_release);
}

std::string system_error(const std::string& what, int error) { return what + ": " + std::strerror(error); }

[[noreturn]] void fail(const std::string& path, const std::string& what) { throw FileError(path, 0, 0, what); }

// The name a regular file is finally known by, following symbolic links (a dangling link leads to
// the name to create).
std::string follow_links(const std::string& path) {
  std::string current = path;
  for (int hops = 0; hops < 40; ++hops) {
    struct stat st {};
    if (::lstat(current.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return current;
    std::vector<char> buffer(static_cast<std::size_t>(st.st_size > 0 ? st.st_size : 255) + 1);
    const ssize_t n = ::readlink(current.c_str(), buffer.data(), buffer.size());
    if (n < 0) fail(path, system_error("cannot read the symbolic link " + current, errno));
    const fs::path link(std::string(buffer.data(), static_cast<std::size_t>(n)));
    current = link.is_absolute() ? link.string() : (fs::path(current).parent_path() / link).string();
  }
  fail(path, "too many levels of symbolic links");
}

bool same_file_as_descriptor(const struct stat& st, int fd) {
  struct stat other {};
  return ::fstat(fd, &other) == 0 && other.st_dev == st.st_dev && other.st_ino == st.st_ino;
}

std::string random_suffix() {
  static std::atomic<unsigned> counter{0};
  static const char alphabet[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  // Seeded from the system's entropy source, this process and a per-process counter, so that two
  // writers of the same file (threads or processes) pick different names.
  std::random_device device;
  const std::uint64_t entropy = (std::uint64_t{device()} << 32) ^ device();
  Rng rng(entropy ^ (std::uint64_t{counter.fetch_add(1)} * 0x9e3779b97f4a7c15ull) ^
          (static_cast<std::uint64_t>(::getpid()) << 17));
  std::string s(6, 'a');
  for (char& c : s) c = alphabet[rng.below(sizeof(alphabet) - 1)];
  return s;
}

}  // namespace

// ---- a stream buffer over a file descriptor that remembers the first write error ---------------

class AtomicFile::Buffer : public std::streambuf {
 public:
  explicit Buffer(int fd) : fd_(fd), data_(1 << 16) { reset(); }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type ch) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(ch, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(ch);
      pbump(1);
    }
    return traits_type::not_eof(ch);
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    if (n <= epptr() - pptr()) {
      std::memcpy(pptr(), s, static_cast<std::size_t>(n));
      pbump(static_cast<int>(n));
      return n;
    }
    if (!drain() || !write_all(s, static_cast<std::size_t>(n))) return 0;
    return n;
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  void reset() { setp(data_.data(), data_.data() + data_.size()); }
  bool write_all(const char* p, std::size_t n) {
    while (n > 0) {
      const ssize_t written = ::write(fd_, p, n);
      if (written < 0) {
        if (errno == EINTR) continue;
        error_ = errno;
        return false;
      }
      p += written;
      n -= static_cast<std::size_t>(written);
    }
    return true;
  }
  bool drain() {
    if (error_ != 0) return false;
    const bool ok = write_all(pbase(), static_cast<std::size_t>(pptr() - pbase()));
    reset();
    return ok;
  }
  int fd_;
  std::vector<char> data_;
  int error_ = 0;
};

// ---- AtomicFile -------------------------------------------------------------------------------

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  if (path_.empty()) throw InputError("an output file name is empty");
  if (is_standard_stream(path_)) {
    out_ = &std::cout;
    return;
  }
  struct stat st {};
  const bool exists = ::stat(path_.c_str(), &st) == 0;
  if (!exists && errno != ENOENT) fail(path_, system_error("cannot write", errno));
  bool direct = false;
  if (exists) {
    if (S_ISDIR(st.st_mode)) fail(path_, "is a directory, not a file");
    if (S_ISSOCK(st.st_mode)) fail(path_, "is a socket: cannot write a file there");
    if (::access(path_.c_str(), W_OK) != 0) fail(path_, system_error("cannot write", errno));
    // A regular file that is this process's standard output (e.g. -o /dev/stdout redirected to a
    // file by the shell) is written as standard output, in order with everything else printed.
    if (S_ISREG(st.st_mode) && same_file_as_descriptor(st, STDOUT_FILENO)) {
      out_ = &std::cout;
      return;
    }
    // FIFOs and devices are written, never replaced; so is a regular file that is standard error.
    direct = !S_ISREG(st.st_mode) || same_file_as_descriptor(st, STDERR_FILENO);
  }
  if (direct) {
    target_ = path_;
    fd_ = ::open(path_.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC | (S_ISREG(st.st_mode) ? O_APPEND : 0));
    if (fd_ < 0) fail(path_, system_error("cannot open for writing", errno));
  } else {
    target_ = follow_links(path_);
    fs::path folder = fs::path(target_).parent_path();
    if (folder.empty()) folder = ".";
    std::call_once(g_install_once, install_handlers);
    // Replacing a file: private until it has the old file's mode. A new file: the umask applies.
    const mode_t create_mode = exists ? 0600 : 0666;
    for (int attempt = 0; attempt < 100 && fd_ < 0; ++attempt) {
      const std::string candidate = (folder / (".rb" + random_suffix())).string();
      SignalBlock block;
      fd_ = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOCTTY | O_CLOEXEC, create_mode);
      if (fd_ >= 0) {
        temporary_ = candidate;
        slot_ = acquire_slot(candidate);
      } else if (errno != EEXIST) {
        const int error = errno;
        struct stat folder_stat {};
        if (::stat(folder.c_str(), &folder_stat) != 0) fail(path_, system_error("folder " + folder.string(), error));
        fail(path_, system_error("cannot create a temporary file in " + folder.string(), error));
      }
    }
    if (fd_ < 0) fail(path_, "cannot create a temporary file in " + folder.string());
    if (exists) {
      if (st.st_uid != ::geteuid() || st.st_gid != ::getegid()) {
        if (::fchown(fd_, st.st_uid, st.st_gid) != 0) (void)!::fchown(fd_, static_cast<uid_t>(-1), st.st_gid);
      }
      if (::fchmod(fd_, st.st_mode & 07777) != 0) fail(path_, system_error("cannot keep the file's mode", errno));
    }
  }
  buffer_ = std::make_unique<Buffer>(fd_);
  own_stream_ = std::make_unique<std::ostream>(buffer_.get());
  own_stream_->precision(17);
  out_ = own_stream_.get();
}

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_ && !temporary_.empty()) {
    SignalBlock block;
    ::unlink(temporary_.c_str());
    release_slot(slot_);
  }
}

void AtomicFile::commit() {
  if (committed_) return;
  if (!own_stream_) {
    flush_standard_output();
    committed_ = true;
    return;
  }
  own_stream_->flush();
  if (buffer_->error() != 0) fail(path_, system_error("write failed", buffer_->error()));
  if (!*own_stream_) fail(path_, "write failed");
  if (!temporary_.empty() && ::fsync(fd_) != 0) fail(path_, system_error("write failed (fsync)", errno));
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail(path_, system_error("write failed (close)", errno));
  if (!temporary_.empty()) {
    {
      SignalBlock block;
      if (::rename(temporary_.c_str(), target_.c_str()) != 0) {
        fail(path_, system_error("cannot move the temporary file into place", errno));
      }
      release_slot(slot_);
      slot_ = -1;
    }
    // Make the rename itself durable (best effort: not every file system supports it).
    fs::path folder = fs::path(target_).parent_path();
    if (folder.empty()) folder = ".";
    const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dir >= 0) {
      (void)::fsync(dir);
      ::close(dir);
    }
  }
  committed_ = true;
}

void flush_standard_output() {
  errno = 0;
  std::cout.flush();
  const bool stream_failed = !std::cout;
  const bool flush_failed = std::fflush(stdout) != 0;
  const int error = errno;
  if (stream_failed || flush_failed || std::ferror(stdout)) {
    std::cout.clear();
    std::clearerr(stdout);
    throw FileError(kStandardOutputName, 0, 0,
                    error != 0 ? system_error("write failed", error)
                               : std::string("write failed (an earlier write was refused: the output is incomplete)"));
  }
}

// ---- inputs and outputs of one command -------------------------------------------------------

namespace {

struct Identity {
  bool exists = false;
  bool regular = false;
  dev_t device = 0;
  ino_t inode = 0;
  std::string normal;  // absolute, symbolic links of existing parts resolved
};

Identity identify(const std::string& path) {
  Identity id;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    id.exists = true;
    id.regular = S_ISREG(st.st_mode);
    id.device = st.st_dev;
    id.inode = st.st_ino;
  }
  std::error_code ec;
  id.normal = fs::weakly_canonical(fs::absolute(path, ec), ec).string();
  if (ec) id.normal = path;
  return id;
}

bool same(const Identity& a, const Identity& b) {
  if (a.exists && b.exists) return a.device == b.device && a.inode == b.inode;
  if (!a.exists && !b.exists) return a.normal == b.normal;
  return false;
}

std::string quoted(const FileArgument& f) { return f.role + " '" + f.path + "'"; }

}  // namespace

void check_distinct_files(const std::vector<FileArgument>& inputs, const std::vector<FileArgument>& outputs) {
  const FileArgument* standard_input = nullptr;
  std::vector<std::pair<const FileArgument*, Identity>> input_ids;
  for (const FileArgument& in : inputs) {
    if (in.path.empty()) continue;
    if (is_standard_stream(in.path)) {
      if (standard_input) {
        throw InputError("standard input ('-') is given twice (" + standard_input->role + " and " + in.role +
                         "): it can be read only once");
      }
      standard_input = &in;
      continue;
    }
    Identity id = identify(in.path);
    if (id.exists && id.regular) input_ids.emplace_back(&in, std::move(id));
  }
  const FileArgument* standard_output = nullptr;
  std::vector<std::pair<const FileArgument*, Identity>> output_ids;
  for (const FileArgument& out : outputs) {
    if (out.path.empty()) continue;
    if (is_standard_stream(out.path)) {
      if (standard_output) {
        throw InputError("standard output ('-') is given twice (" + standard_output->role + " and " + out.role +
                         "): the two outputs would be mixed");
      }
      standard_output = &out;
      continue;
    }
    Identity id = identify(out.path);
    if (id.exists && !id.regular) continue;  // /dev/null and the like may repeat; nothing is replaced
    for (const auto& [in, in_id] : input_ids) {
      if (same(id, in_id)) {
        throw InputError("output " + quoted(out) + " is the same file as the input " + quoted(*in) +
                         ": refusing to overwrite an input (choose another output file)");
      }
    }
    for (const auto& [other, other_id] : output_ids) {
      if (same(id, other_id)) {
        throw InputError("outputs " + quoted(*other) + " and " + quoted(out) +
                         " are the same file: one would overwrite the other");
      }
    }
    output_ids.emplace_back(&out, std::move(id));
  }
}

}  // namespace roadbrdf
