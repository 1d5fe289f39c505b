// Inputs that are endless, huge, of the wrong kind or oddly blank, and request counts beyond what
// memory and time allow: each is refused with a located message (or read as the blank it is),
// never a crash, an exhausted memory or a wait without end.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/input_file.h"
#include "roadbrdf/core/text.h"
#include "roadbrdf/fitting/fit_request.h"
#include "roadbrdf/formulation/formulation.h"
#include "roadbrdf/io/calibration.h"
#include "roadbrdf/io/instrument.h"
#include "roadbrdf/io/manifest.h"
#include "roadbrdf/io/sed.h"
#include "roadbrdf/io/sig.h"
#include "roadbrdf/surface/render_request.h"
#include "support/paths.h"
#include "support/scratch.h"

namespace roadbrdf {
namespace {

namespace fs = std::filesystem;

template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

template <typename F>
std::string field_of(F&& f) {
  try {
    f();
  } catch (const FieldError& e) {
    return e.field();
  }
  return "(no FieldError)";
}

// Every string of up to 4 characters from blanks, a vertical tab and a letter: trimming and the
// whitespace splitter agree on which are blank (a line the splitter finds empty is skipped as blank).
TEST(BlankRule, TrimAndSplitAgreeOnEveryShortString) {
  const std::string alphabet = std::string(" \t\r\v") + "a";
  std::vector<std::string> strings = {""};
  for (int length = 1; length <= 4; ++length) {
    const std::size_t n = strings.size();
    for (std::size_t k = 0; k < n; ++k) {
      if (strings[k].size() + 1 != static_cast<std::size_t>(length)) continue;
      for (char c : alphabet) strings.push_back(strings[k] + c);
    }
  }
  for (const std::string& s : strings) {
    EXPECT_EQ(trim_blanks(s).empty(), split_whitespace(s).empty()) << '"' << s << '"';
    for (const CsvCell& cell : split_whitespace(s)) EXPECT_EQ(trim_blanks(cell.text), cell.text);
  }
  EXPECT_EQ(trim_blanks("\r"), "");
  EXPECT_EQ(trim_blanks(" \t x \r"), "x");
}

const std::string kSig = "/*** Spectra Vista SIG Data ***/\nunits= Counts, Counts\ndata=\n400 10 5 50\n410 20 8 40\n";

TEST(SigReader, LineOfOnlyCarriageReturnsIsBlank) {
  for (const std::string blank : {"\r\r\n", "\r\n", " \r \t\r\n"}) {
    std::string text = kSig;
    text.insert(text.find("410"), blank);
    const InstrumentSpectrum s = parse_sig(text, "cr.sig", OverlapRule::kError);
    EXPECT_EQ(s.wavelengths, (std::vector<double>{400, 410}));
    EXPECT_EQ(s.reflectance, (std::vector<double>{0.5, 0.4}));
  }
}

const std::string kSed = "Version: 2.3\nChannels: CHANNELS\nData:\nWvl\tReflect. %\n400\t50\n410\t40\n";

std::string sed_with(const std::string& channels) {
  std::string text = kSed;
  return text.replace(text.find("CHANNELS"), 8, channels);
}

TEST(SedReader, ChannelCountBeyondTheLimitIsRefusedBeforeAnyCast) {
  EXPECT_EQ(parse_sed(sed_with("2"), "ok.sed").wavelengths.size(), 2u);
  for (const std::string n : {"1e30", "1e19", "18446744073709551616", "1000001"}) {
    const std::string e = error_of([&] { parse_sed(sed_with(n), "big.sed"); });
    EXPECT_NE(e.find("big.sed:2"), std::string::npos) << e;
    EXPECT_NE(e.find("'Channels: " + n + "' is more than the 1000000 channels"), std::string::npos) << e;
  }
  // A count within the limit still checks the rows (truncation).
  const std::string e = error_of([&] { parse_sed(sed_with("3"), "short.sed"); });
  EXPECT_NE(e.find("2 data rows, but line 2 says 'Channels: 3'"), std::string::npos) << e;
  // A carriage return alone on a line is blank here too.
  std::string cr = sed_with("2");
  cr.insert(cr.find("410"), "\r\r\n");
  EXPECT_EQ(parse_sed(cr, "cr.sed").wavelengths.size(), 2u);
}

// A FIFO where a regular file is required is refused without waiting for a writer. Should the
// check ever be lost, the writer thread keeps opening the FIFO's other end and closing it, so that
// every blocked reader sees an empty file and the test fails instead of hanging.
class Fifo {
 public:
  explicit Fifo(const std::string& path) : path_(path) {
    fs::remove(path_);
    EXPECT_EQ(::mkfifo(path_.c_str(), 0600), 0);
    writer_ = std::thread([this] {
      while (!done_) {
        const int fd = ::open(path_.c_str(), O_WRONLY | O_NONBLOCK);
        if (fd >= 0) ::close(fd);
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
    });
  }
  ~Fifo() {
    done_ = true;
    writer_.join();
    fs::remove(path_);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::atomic<bool> done_{false};
  std::thread writer_;
};

TEST(InputFileLimits, FifoIsRefusedWhereARegularFileIsRequired) {
  const Fifo fifo(test::scratch_path("input.fifo"));
  InputLimits regular;
  regular.what = "a test file";
  regular.regular_file_only = true;
  std::string e = error_of([&] { InputFile in(fifo.path(), regular); });
  EXPECT_NE(e.find("is a FIFO (named pipe), not a regular file: a test file must be a regular file"), std::string::npos)
      << e;
  e = error_of([&] { read_manifest(fifo.path()); });
  EXPECT_NE(e.find("is a FIFO (named pipe), not a regular file: a run manifest must be a regular file"),
            std::string::npos)
      << e;
  e = error_of([&] { read_panel_reflectance(fifo.path()); });
  EXPECT_NE(e.find("a panel reflectance file must be a regular file"), std::string::npos) << e;
  InstrumentReadOptions listed;
  listed.regular_file_only = true;
  e = error_of([&] { read_instrument_file(fifo.path(), listed); });
  EXPECT_NE(e.find("must be a regular file"), std::string::npos) << e;
  e = error_of([&] { InputFile in("/dev/null", regular); });
  EXPECT_NE(e.find("is a character device, not a regular file"), std::string::npos) << e;
}

// A manifest whose entry is a FIFO: the entry is refused when the run is read.
TEST(InputFileLimits, ManifestEntryThatIsAFifoIsRefused) {
  const std::string dir = test::scratch_path("fifo-run");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const Fifo fifo(dir + "/white.asd");
  std::ofstream(dir + "/run.csv") << "file,role,gamma,alpha,beta,delta\nwhite.asd,white,,,,\n"
                                  << test::instrument_files_dir() << "/run_001.asd,sample,0,45,0,0\n";
  const Manifest m = read_manifest(dir + "/run.csv");
  const std::string e = error_of([&] { manifest_calibration_input(m); });
  EXPECT_NE(e.find("white.asd"), std::string::npos) << e;
  EXPECT_NE(e.find("is a FIFO (named pipe), not a regular file"), std::string::npos) << e;
}

TEST(InputFileLimits, EndlessDeviceStopsAtTheLineAndSizeLimits) {
  InputLimits limits;
  limits.what = "a test file";
  limits.max_line_bytes = 1 << 20;
  limits.max_bytes = 8 << 20;
  {
    InputFile in("/dev/zero", limits);
    std::string_view line;
    const std::string e = error_of([&] { in.read_line(line); });
    EXPECT_NE(e.find("/dev/zero:1: line longer than 1048576 bytes (1 MiB) without a line end: not a test file"),
              std::string::npos)
        << e;
  }
  {
    InputFile in("/dev/zero", limits);
    const std::string e = error_of([&] { in.read_all(); });
    EXPECT_NE(e.find("more than the 8388608 bytes (8 MiB) a test file may hold"), std::string::npos) << e;
  }
  // The defaults of every reader: a dataset from /dev/zero fails at the default line limit.
  const std::string e = error_of([] {
    CsvReader reader("/dev/zero");
    std::vector<CsvCell> cells;
    reader.next_row(cells);
  });
  EXPECT_NE(e.find("line longer than 67108864 bytes (64 MiB)"), std::string::npos) << e;
}

// A sparse 3 GiB .asd (nothing stored on the disk) is refused from its size before it is read.
TEST(InputFileLimits, HugeInstrumentFileIsRefusedFromItsSize) {
  const std::string path = test::scratch_path("sparse.asd");
  std::ofstream(path) << "as7";
  fs::resize_file(path, std::uintmax_t{3} << 30);
  const std::string e = error_of([&] { read_instrument_file(path); });
  fs::remove(path);
  EXPECT_NE(e.find("file is 3221225472 bytes (3 GiB), more than the 16777216 bytes (16 MiB) an instrument file"),
            std::string::npos)
      << e;
}

TEST(InputEnumeration, ManifestListsEveryFileItNames) {
  const std::string dir = test::instrument_files_dir();
  const std::vector<FileArgument> files = manifest_input_files(read_manifest(dir + "/run.csv"));
  std::vector<std::string> paths;
  for (const FileArgument& f : files) paths.push_back(fs::path(f.path).filename().string());
  EXPECT_EQ(paths,
            (std::vector<std::string>{"run_white.asd", "run_dark.asd", "run_001.asd", "run_002.asd", "run_003.asd"}));
  EXPECT_NE(files[0].role.find("white reference file 'run_white.asd'"), std::string::npos) << files[0].role;
  EXPECT_NE(files[0].role.find("run.csv:3"), std::string::npos) << files[0].role;
}

TEST(InputEnumeration, FormulationListsItsFitFiles) {
  const std::string path = test::scratch_path("enumerated.formulation.json");
  std::ofstream(path) << R"({"format": "roadbrdf-formulation", "version": 1, "name": "T",
    "mastic": {"name": "M", "fit": "mastic.fit.json"},
    "components": [{"name": "Grey", "kind": "binder", "mass_percent": 60, "density_g_cm3": 1.0, "fit": "grey.fit.json"},
                   {"name": "Stone", "kind": "aggregate", "mass_percent": 40, "density_g_cm3": 2.7,
                    "d_min_mm": 4, "d_max_mm": 6, "fit": "sub/stone.fit.json"}]})";
  const std::vector<FileArgument> files = formulation_input_files(read_formulation(path, false));
  const std::string folder = fs::path(path).parent_path().string();
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(files[0].path, folder + "/mastic.fit.json");
  EXPECT_EQ(files[1].path, folder + "/grey.fit.json");
  EXPECT_EQ(files[1].role, "fit of component 'Grey'");
  EXPECT_EQ(files[2].path, folder + "/sub/stone.fit.json");
}

TEST(RequestCounts, FitCountsBeyondTheirLimitsNameTheField) {
  auto with = [](auto change) {
    FitRequest r;
    r.models = {"lambert"};
    change(r);
    return field_of([&] { r.validate(); });
  };
  EXPECT_EQ(with([](FitRequest& r) { r.multistart = 10000; }), "(no FieldError)");
  EXPECT_EQ(with([](FitRequest& r) { r.multistart = 1000000000; }), "multistart");
  EXPECT_EQ(with([](FitRequest& r) { r.multistart = 0; }), "multistart");
  EXPECT_EQ(with([](FitRequest& r) { r.threads = 100000; }), "threads");
  EXPECT_EQ(with([](FitRequest& r) { r.max_iterations = 2000000000; }), "max_iterations");
  FitRequest r;
  r.models = {"lambert"};
  r.multistart = 1000000000;
  const std::string e = error_of([&] { r.validate(); });
  EXPECT_NE(e.find("multistart: 1000000000 is outside [1, 10000]"), std::string::npos) << e;
}

TEST(RequestCounts, RenderPathCountsBeyondTheLimitNameTheField) {
  surface::RenderRequest r;
  r.samples = 99999999999L;
  EXPECT_EQ(field_of([&] { surface::render_settings(r); }), "samples");
  const std::string e = error_of([&] { surface::render_settings(r); });
  EXPECT_NE(e.find("samples: 99999999999 is above the limit of 1073741824 paths per geometry"), std::string::npos) << e;
  r.samples = 1L << 30;
  EXPECT_EQ(field_of([&] { surface::render_settings(r); }), "(no FieldError)");
  r.samples.reset();
  r.target_error = 0.01;
  r.max_samples = (1L << 30) + 1;
  EXPECT_EQ(field_of([&] { surface::render_settings(r); }), "max_samples");
}

}  // namespace
}  // namespace roadbrdf
