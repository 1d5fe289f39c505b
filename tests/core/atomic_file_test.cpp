// AtomicFile and check_distinct_files (core/atomic_file.h): the rules for output files.
#include "roadbrdf/core/atomic_file.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "roadbrdf/core/error.h"
#include "support/full_disk.h"
#include "support/scratch.h"

namespace roadbrdf {
namespace {

namespace fs = std::filesystem;

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_plain(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// A fresh folder of its own for each test (to list what is left in it).
std::string folder(const std::string& name) {
  const std::string dir = test::scratch_path(name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::vector<std::string> names_in(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

mode_t mode_of(const std::string& path) {
  struct stat st {};
  EXPECT_EQ(::lstat(path.c_str(), &st), 0);
  return st.st_mode;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(AtomicFile, ReplacesAFileAndLeavesNoTemporary) {
  const std::string dir = folder("replace");
  const std::string path = dir + "/out.csv";
  write_plain(path, "old\n");
  {
    AtomicFile f(path);
    f.stream() << "new " << 0.1 << '\n';
    EXPECT_EQ(read(path), "old\n");  // nothing visible before the commit
    f.commit();
  }
  EXPECT_EQ(read(path), "new 0.10000000000000001\n");  // 17 significant digits
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"out.csv"});
}

TEST(AtomicFile, WithoutCommitTheTargetIsUntouchedAndTheTemporaryRemoved) {
  const std::string dir = folder("abandon");
  const std::string path = dir + "/out.csv";
  write_plain(path, "old\n");
  {
    AtomicFile f(path);
    f.stream() << "half";
    EXPECT_EQ(names_in(dir).size(), 2u);  // the temporary file exists meanwhile
  }
  EXPECT_EQ(read(path), "old\n");
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"out.csv"});
}

TEST(AtomicFile, KeepsTheModeOfTheFileItReplaces) {
  const std::string dir = folder("mode");
  const std::string path = dir + "/out.csv";
  write_plain(path, "old\n");
  ASSERT_EQ(::chmod(path.c_str(), 0640), 0);
  AtomicFile f(path);
  f.stream() << "new\n";
  f.commit();
  EXPECT_EQ(mode_of(path) & 07777, 0640u);
}

TEST(AtomicFile, NewFileGetsTheUmaskMode) {
  const std::string dir = folder("umask");
  const mode_t old = ::umask(027);
  {
    AtomicFile f(dir + "/new.csv");
    f.stream() << "x\n";
    f.commit();
  }
  ::umask(old);
  EXPECT_EQ(mode_of(dir + "/new.csv") & 07777, 0640u);
}

TEST(AtomicFile, ReadOnlyFileIsRefusedOrKeepsItsMode) {
  const std::string dir = folder("readonly");
  const std::string path = dir + "/ro.csv";
  write_plain(path, "old\n");
  ASSERT_EQ(::chmod(path.c_str(), 0444), 0);
  if (::geteuid() != 0) {
    const std::string message = error_of([&] { AtomicFile f(path); });
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("Permission denied"), std::string::npos) << message;
    EXPECT_EQ(read(path), "old\n");
  } else {  // root may write it: the mode must survive
    AtomicFile f(path);
    f.stream() << "new\n";
    f.commit();
    EXPECT_EQ(mode_of(path) & 07777, 0444u);
  }
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"ro.csv"});
}

TEST(AtomicFile, WritesThroughASymbolicLinkAndKeepsIt) {
  const std::string dir = folder("symlink");
  fs::create_directories(dir + "/data");
  write_plain(dir + "/data/target.csv", "old\n");
  fs::create_symlink("data/target.csv", dir + "/link.csv");
  fs::create_symlink("link.csv", dir + "/link2.csv");  // a chain
  AtomicFile f(dir + "/link2.csv");
  f.stream() << "new\n";
  f.commit();
  EXPECT_TRUE(fs::is_symlink(dir + "/link.csv"));
  EXPECT_TRUE(fs::is_symlink(dir + "/link2.csv"));
  EXPECT_EQ(read(dir + "/data/target.csv"), "new\n");
  EXPECT_EQ(names_in(dir + "/data"), std::vector<std::string>{"target.csv"});
  EXPECT_EQ(names_in(dir), (std::vector<std::string>{"data", "link.csv", "link2.csv"}));
}

TEST(AtomicFile, DanglingLinkGetsItsTargetCreated) {
  const std::string dir = folder("dangling");
  fs::create_symlink("made.csv", dir + "/link.csv");
  AtomicFile f(dir + "/link.csv");
  f.stream() << "new\n";
  f.commit();
  EXPECT_TRUE(fs::is_symlink(dir + "/link.csv"));
  EXPECT_EQ(read(dir + "/made.csv"), "new\n");
}

TEST(AtomicFile, FifoIsWrittenNotReplaced) {
  const std::string dir = folder("fifo");
  const std::string path = dir + "/pipe";
  ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = read(path); });
  {
    AtomicFile f(path);
    f.stream() << "through the pipe\n";
    f.commit();
  }
  reader.join();
  EXPECT_EQ(received, "through the pipe\n");
  EXPECT_TRUE(S_ISFIFO(mode_of(path)));
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"pipe"});
}

TEST(AtomicFile, DeviceIsWrittenNotReplaced) {
  struct stat before {};
  ASSERT_EQ(::stat("/dev/null", &before), 0);
  AtomicFile f("/dev/null");
  f.stream() << "discarded\n";
  f.commit();
  struct stat after {};
  ASSERT_EQ(::stat("/dev/null", &after), 0);
  EXPECT_TRUE(S_ISCHR(after.st_mode));
  EXPECT_EQ(before.st_ino, after.st_ino);
}

TEST(AtomicFile, FullDeviceIsAnErrorNamingThePath) {
  if (!test::dev_full_refuses_writes()) GTEST_SKIP() << test::kNoFullDevice;
  AtomicFile f("/dev/full");
  for (int k = 0; k < 100000; ++k) f.stream() << "0123456789\n";
  const std::string message = error_of([&] { f.commit(); });
  EXPECT_NE(message.find("/dev/full"), std::string::npos) << message;
  EXPECT_NE(message.find("No space left on device"), std::string::npos) << message;
}

// A disk that fills up during the write, on any machine: a child process with a 4 KiB file-size
// limit (and SIGXFSZ ignored) writes 1.1 MB; the error names the target and nothing is left.
TEST(AtomicFile, WriteRefusedMidwayIsAnErrorAndLeavesNothing) {
  const std::string dir = folder("file-size-limit");
  const std::string path = dir + "/out.csv";
  int channel[2];
  ASSERT_EQ(::pipe(channel), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::close(channel[0]);
    ::signal(SIGXFSZ, SIG_IGN);
    const struct rlimit limit { 4096, 4096 };
    ::setrlimit(RLIMIT_FSIZE, &limit);
    std::string message = "no error";
    try {
      AtomicFile f(path);
      for (int k = 0; k < 100000; ++k) f.stream() << "0123456789\n";
      f.commit();
    } catch (const InputError& e) {
      message = e.what();
    }
    const ssize_t written = ::write(channel[1], message.data(), message.size());
    ::_exit(written == static_cast<ssize_t>(message.size()) ? 0 : 1);
  }
  ::close(channel[1]);
  std::string message;
  char buffer[512];
  for (ssize_t n; (n = ::read(channel[0], buffer, sizeof buffer)) > 0;) message.append(buffer, n);
  ::close(channel[0]);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find(test::kFileTooLarge), std::string::npos) << message;
  EXPECT_EQ(names_in(dir), std::vector<std::string>{});
}

TEST(AtomicFile, DirectoryIsAnError) {
  const std::string dir = folder("directory");
  const std::string message = error_of([&] { AtomicFile f(dir); });
  EXPECT_NE(message.find("is a directory"), std::string::npos) << message;
}

TEST(AtomicFile, MissingFolderIsAnErrorNamingIt) {
  const std::string dir = folder("missing");
  const std::string message = error_of([&] { AtomicFile f(dir + "/no/such/out.csv"); });
  EXPECT_NE(message.find(dir + "/no/such"), std::string::npos) << message;
  EXPECT_NE(message.find("No such file or directory"), std::string::npos) << message;
}

TEST(AtomicFile, NameAtTheLengthLimitStillWorks) {
  const std::string dir = folder("long");
  const std::string path = dir + "/" + std::string(250, 'n') + ".csv";  // 254 characters: the limit is 255
  AtomicFile f(path);
  f.stream() << "x\n";
  f.commit();
  EXPECT_EQ(read(path), "x\n");
  EXPECT_EQ(names_in(dir).size(), 1u);
}

// Runs `body` in a child process; returns its wait status.
int in_child(const std::function<void()>& body) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    body();
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

TEST(AtomicFile, TerminationSignalRemovesTheTemporaryFile) {
  for (int signal_number : {SIGTERM, SIGINT}) {
    const std::string dir = folder("signal" + std::to_string(signal_number));
    const int status = in_child([&] {
      AtomicFile f(dir + "/out.csv");
      f.stream() << "partial" << std::flush;
      if (names_in(dir).size() != 1) ::_exit(10);  // the temporary file must exist here
      ::raise(signal_number);
      ::_exit(11);  // not reached: the default action ends the process
    });
    ASSERT_TRUE(WIFSIGNALED(status)) << "status " << status;
    EXPECT_EQ(WTERMSIG(status), signal_number);
    EXPECT_TRUE(names_in(dir).empty());
  }
}

volatile sig_atomic_t g_handled = 0;
extern "C" void count_signal(int) { g_handled = g_handled + 1; }

// (Meaningful when no AtomicFile was made before in this process, as under ctest: one test per process.)
TEST(AtomicFile, HandlerInstalledBeforeIsCalledAndTheWriteGoesOn) {
  const std::string dir = folder("chained");
  const int status = in_child([&] {
    ::signal(SIGINT, count_signal);  // as the Python interpreter does
    AtomicFile f(dir + "/out.csv");
    f.stream() << "complete\n";
    ::raise(SIGINT);
    if (g_handled != 1) ::_exit(12);
    f.commit();
    ::_exit(read(dir + "/out.csv") == "complete\n" ? 0 : 13);
  });
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"out.csv"});
}

TEST(AtomicFile, IgnoredSignalStaysIgnored) {
  const std::string dir = folder("ignored");
  const int status = in_child([&] {
    ::signal(SIGTERM, SIG_IGN);
    AtomicFile f(dir + "/out.csv");
    f.stream() << "complete\n";
    ::raise(SIGTERM);
    f.commit();
  });
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(read(dir + "/out.csv"), "complete\n");
}

// ---- check_distinct_files -------------------------------------------------------------------

TEST(DistinctFiles, OutputThatIsAnInputIsRefused) {
  const std::string dir = folder("distinct");
  const std::string data = dir + "/data.csv";
  write_plain(data, "x\n");
  fs::create_symlink("data.csv", dir + "/alias.csv");
  fs::create_hard_link(data, dir + "/hard.csv");
  for (const std::string& output : {data, dir + "/alias.csv", dir + "/hard.csv", dir + "/./data.csv"}) {
    const std::string message = error_of([&] { check_distinct_files({{"DATA", data}}, {{"-o", output}}); });
    EXPECT_NE(message.find("-o '" + output + "'"), std::string::npos) << message;
    EXPECT_NE(message.find("DATA '" + data + "'"), std::string::npos) << message;
    EXPECT_NE(message.find("refusing to overwrite an input"), std::string::npos) << message;
  }
  EXPECT_EQ(read(data), "x\n");
  EXPECT_EQ(error_of([&] { check_distinct_files({{"DATA", data}}, {{"-o", dir + "/other.csv"}}); }), "");
}

TEST(DistinctFiles, TwoOutputsNamingOneFileAreRefused) {
  const std::string dir = folder("two-outputs");
  const std::string message = error_of([&] {
    check_distinct_files({}, {{"-o", dir + "/a.csv"}, {"--residuals", dir + "/../two-outputs/a.csv"}});
  });
  EXPECT_NE(message.find("are the same file"), std::string::npos) << message;
  EXPECT_EQ(error_of([&] { check_distinct_files({}, {{"-o", "/dev/null"}, {"--residuals", "/dev/null"}}); }), "");
}

TEST(DistinctFiles, StandardStreamsAtMostOnce) {
  EXPECT_NE(error_of([] {
              check_distinct_files({{"A", "-"}, {"B", "-"}}, {});
            }).find("standard input"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              check_distinct_files({}, {{"-o", "-"}, {"--residuals", "-"}});
            }).find("standard output"),
            std::string::npos);
  EXPECT_EQ(error_of([] { check_distinct_files({{"A", "-"}}, {{"-o", "-"}}); }), "");
}

}  // namespace
}  // namespace roadbrdf
