// Adversarial command lines that used to lose a user's data: an output that
// is an input, unchecked writes to standard output and full disks, AtomicFile replacing links,
// FIFOs and read-only files, read errors taken for the end of a file. Every refused case asserts a
// clear message naming the file, a non-zero exit, no input modified and no temporary file left.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "support/case_folder.h"
#include "support/cli.h"
#include "support/full_disk.h"
#include "support/paths.h"

namespace roadbrdf {
namespace {

namespace fs = std::filesystem;
using test::CaseFolder;
using test::refused_with;
using test::run_cli;

const std::string kLambertFit = R"({"format": "roadbrdf-fit", "version": 1, "best": "lambert",
  "fits": [{"model": "lambert", "options": {}, "wavelengths": [400, 500, 600, 700, 800],
            "parameters": {"albedo": [0.2, 0.25, 0.3, 0.3, 0.3]}}]})";
const std::string kGrid = "theta_i,phi_i,theta_r,phi_r\n0,0,30,180\n30,0,0,0\n30,0,30,180\n";
const std::string kFormulation = R"({"format": "roadbrdf-formulation", "version": 1, "name": "T",
  "components": [{"name": "Grey", "kind": "binder", "mass_percent": 100, "density_g_cm3": 1.0,
                  "fit": "lambert.fit.json"}]})";

// A folder with one input of every kind.
CaseFolder inputs(const std::string& name) {
  CaseFolder f(name);
  f.copy(test::test_data_dir() + "/io/wide_small.csv", "data.csv");
  f.write("lambert.fit.json", kLambertFit);
  f.write("grid.csv", kGrid);
  f.write("F.json", kFormulation);
  return f;
}

TEST(CliDataLoss, OutputThatIsAnInputIsRefusedBeforeAnyWork) {
  CaseFolder f = inputs("same-file");
  const auto r_table = run_cli("rtable lambert -p albedo=0.3 -o " + f.path("r.csv"));
  ASSERT_EQ(r_table.status, 0) << r_table.output;
  ASSERT_EQ(run_cli("surface lambert --flat -o " + f.path("flat.json")).status, 0);
  fs::create_symlink("data.csv", f.path("alias.csv"));
  fs::create_hard_link(f.path("data.csv"), f.path("hard.csv"));
  f.snapshot();
  const std::string data = f.path("data.csv");
  struct Case {
    std::string arguments, output_role, output, input_role, input;
  };
  const std::vector<Case> cases = {
      // fit and mix spell their fields from their request tables: an output is named by its long flag.
      {"fit " + data + " -m lambert -o " + data, "--output", data, "DATA", data},
      {"fit " + data + " -m lambert -o " + f.path("fit.json") + " --residuals " + data, "--residuals", data, "DATA",
       data},
      {"fit " + data + " -m lambert -o " + f.path("alias.csv"), "--output", f.path("alias.csv"), "DATA", data},
      {"fit " + data + " -m lambert -o " + f.path("hard.csv"), "--output", f.path("hard.csv"), "DATA", data},
      {"convert " + data + " -o " + data, "--output", data, "INPUT", data},
      {"resample " + data + " --wavelengths 500:700:100 -o " + data, "--output", data, "DATA", data},
      {"calibrate " + data + " --reference " + f.path("grid.csv") + " --panel-reflectance " + f.path("r.csv") + " -o " +
           f.path("grid.csv"),
       "--output", f.path("grid.csv"), "--reference", f.path("grid.csv")},
      {"eval lambert --geometry " + f.path("grid.csv") + " -o " + f.path("grid.csv"), "--output", f.path("grid.csv"),
       "--geometry", f.path("grid.csv")},
      {"simulate lambert --grid " + f.path("grid.csv") + " --wavelengths 500:600:50 -o " + f.path("grid.csv"),
       "--output", f.path("grid.csv"), "--grid", f.path("grid.csv")},
      {"simulate " + f.path("lambert.fit.json") + " --grid " + f.path("grid.csv") + " -o " + f.path("lambert.fit.json"),
       "--output", f.path("lambert.fit.json"), "MODEL", f.path("lambert.fit.json")},
      {"rtable --import " + f.path("r.csv") + " -o " + f.path("r.csv"), "--output", f.path("r.csv"), "--import",
       f.path("r.csv")},
      {"albedo " + f.path("lambert.fit.json") + " -o " + f.path("lambert.fit.json"), "-o", f.path("lambert.fit.json"),
       "MODEL", f.path("lambert.fit.json")},
      {"mix " + f.path("F.json") + " -o " + f.path("F.json"), "--output", f.path("F.json"), "FORMULATION",
       f.path("F.json")},
      {"mix " + f.path("F.json") + " -o " + f.path("lambert.fit.json"), "--output", f.path("lambert.fit.json"),
       "fit of component 'Grey'", f.path("lambert.fit.json")},
      {"mix " + f.path("F.json") + " --data " + data + " --residuals " + data + " -o " + f.path("mix.json"),
       "--residuals", data, "--data", data},
      {"mix-calibrate " + f.path("F.json") + " " + data + " -o " + f.path("lambert.fit.json"), "--output",
       f.path("lambert.fit.json"), "fit of component 'Grey'", f.path("lambert.fit.json")},
      {"surface " + f.path("F.json") + " -o " + f.path("F.json"), "--output", f.path("F.json"), "INPUT",
       f.path("F.json")},
      {"render " + f.path("flat.json") + " --albedo 30 -o " + f.path("flat.json"), "--output", f.path("flat.json"),
       "SURFACE", f.path("flat.json")},
  };
  for (const Case& c : cases) {
    const auto r = run_cli(c.arguments);
    EXPECT_TRUE(refused_with(
        r, {c.output_role + " '" + c.output + "' is the same file as the input " + c.input_role + " '" + c.input + "'",
            "refusing to overwrite an input"}))
        << c.arguments;
    EXPECT_EQ(f.changes(), std::vector<std::string>{}) << c.arguments;
  }
  const auto r = run_cli("fit " + data + " -m lambert -o " + f.path("x.json") + " --residuals " + f.path("x.json"));
  EXPECT_TRUE(refused_with(
      r, {"outputs --residuals '" + f.path("x.json") + "' and --output '" + f.path("x.json") + "' are the same file"}));
  EXPECT_EQ(f.changes(), std::vector<std::string>{});
}

// Every file a manifest lists is an input: calibrate and convert refuse an output that is one of
// them, named directly or through a link, before any file is read.
TEST(CliDataLoss, FilesListedInAManifestAreInputs) {
  CaseFolder f("manifest-inputs");
  for (const std::string name :
       {"run.csv", "rho.txt", "run_white.asd", "run_dark.asd", "run_001.asd", "run_002.asd", "run_003.asd"}) {
    f.copy(test::instrument_files_dir() + "/" + name, name);
  }
  fs::create_symlink("run_002.asd", f.path("link.asd"));
  f.snapshot();
  const std::string calibrate =
      "calibrate --manifest " + f.path("run.csv") + " --panel-reflectance " + f.path("rho.txt");
  // calibrate and convert spell their fields from their request tables: an output is named by its long flag.
  struct Case {
    std::string arguments, output_role, output, listed;
  };
  const std::vector<Case> cases = {
      {calibrate + " -o " + f.path("run_white.asd"), "--output", f.path("run_white.asd"),
       "white reference file 'run_white.asd'"},
      {calibrate + " -o " + f.path("link.asd"), "--output", f.path("link.asd"), "sample file 'run_002.asd'"},
      {"convert --from manifest " + f.path("run.csv") + " -o " + f.path("run_dark.asd"), "--output",
       f.path("run_dark.asd"), "dark file 'run_dark.asd'"},
  };
  for (const Case& c : cases) {
    const auto r = run_cli(c.arguments);
    EXPECT_TRUE(refused_with(r, {c.output_role + " '" + c.output + "' is the same file as the input " + c.listed,
                                 f.path("run.csv") + ":", "refusing to overwrite an input"}))
        << c.arguments;
    EXPECT_EQ(f.changes(), std::vector<std::string>{}) << c.arguments;
  }
  // The listed files are still read as before.
  const auto r = run_cli(calibrate + " -o " + f.path("brdf.csv"));
  EXPECT_EQ(r.status, 0) << r.output;
}

// A folder whose data set and geometry grid are large enough to pass the 1-block
// file-size limit in every command's output.
CaseFolder large_inputs(const std::string& name) {
  CaseFolder f = inputs(name);
  std::ostringstream csv, grid;
  csv << "theta_i,phi_i,theta_r,phi_r";
  for (int w = 400; w <= 800; w += 10) csv << ',' << w;
  csv << '\n';
  grid << "theta_i,phi_i,theta_r,phi_r\n";
  for (int t = 0; t <= 60; t += 5) {
    for (int r = 0; r <= 60; r += 20) {
      csv << t << ",0," << r << ",180";
      for (int w = 400; w <= 800; w += 10) csv << ',' << 0.1 + 0.0001 * (w + t);
      csv << '\n';
      grid << t << ",0," << r << ",180\n";
    }
  }
  f.write("data.csv", csv.str());
  f.write("grid.csv", grid.str());
  return f;
}

// Every command that writes to standard output, with a full standard output: /dev/full where the
// machine has a real one, and always a regular file under a file-size limit.
std::vector<std::string> standard_output_commands(const CaseFolder& f) {
  const std::string data = f.path("data.csv");
  return {"convert " + data,
          "eval lambert --geometry " + f.path("grid.csv"),
          "check " + data + " --json",
          "check " + data,
          "rtable lambert",
          "rtable lambert --json",
          "models --json",
          "models",
          "albedo " + f.path("lambert.fit.json"),
          "albedo lambert --json",
          "fit " + data + " -m lambert -o -",
          "convert " + data + " -o -"};
}

TEST(CliDataLoss, FailedWritesToStandardOutputAreErrors) {
  if (!test::dev_full_refuses_writes()) GTEST_SKIP() << test::kNoFullDevice;
  CaseFolder f = inputs("stdout-full");
  f.snapshot();
  for (const std::string& arguments : standard_output_commands(f)) {
    const auto r = test::run_cli_with_stdout(arguments, "/dev/full");
    EXPECT_TRUE(refused_with(r, {"roadbrdf: error: <standard output>: write failed"})) << arguments;
    EXPECT_EQ(f.changes(), std::vector<std::string>{}) << arguments;
  }
}

TEST(CliDataLoss, StandardOutputPastTheFileSizeLimitIsAnError) {
  CaseFolder f = large_inputs("stdout-limit");
  const std::string sink = test::scratch_path("stdout-limit.out");
  const std::uintmax_t limit = test::file_size_limit_bytes(sink);
  for (const std::string& arguments : standard_output_commands(f)) {
    // Precondition: the output is larger than the limit.
    ASSERT_EQ(test::run_cli_with_stdout(arguments, sink).status, 0) << arguments;
    ASSERT_GT(fs::file_size(sink), limit) << arguments << " writes too little to reach the limit";
    f.snapshot();
    const auto r = test::run_cli_with_file_size_limit(arguments, sink);
    // The first refused write may be buffered away from the final check: "write failed" with or
    // without the system's reason.
    EXPECT_TRUE(refused_with(r, {"roadbrdf: error: <standard output>: write failed"})) << arguments;
    EXPECT_EQ(f.changes(), std::vector<std::string>{}) << arguments;
  }
  fs::remove(sink);
}

TEST(CliDataLoss, FullDiskIsAnErrorNamingTheOutput) {
  if (!test::dev_full_refuses_writes()) GTEST_SKIP() << test::kNoFullDevice;
  CaseFolder f = inputs("file-full");
  f.snapshot();
  for (const std::string& arguments : std::vector<std::string>{"convert " + f.path("data.csv") + " -o /dev/full",
                                                               "fit " + f.path("data.csv") + " -m lambert -o /dev/full",
                                                               "rtable lambert -o /dev/full"}) {
    const auto r = run_cli(arguments);
    EXPECT_TRUE(refused_with(r, {"/dev/full: write failed: No space left on device"})) << arguments;
    EXPECT_EQ(f.changes(), std::vector<std::string>{}) << arguments;
  }
}

// A disk that fills up while an output file is written: the error names the output, and neither
// the output nor its temporary file is left in the folder.
TEST(CliDataLoss, OutputFilePastTheFileSizeLimitIsAnErrorAndLeavesNothing) {
  CaseFolder f = large_inputs("file-limit");
  const std::string out = f.path("out");
  const std::uintmax_t limit = test::file_size_limit_bytes(test::scratch_path("file-limit.probe"));
  for (const std::string& arguments :
       std::vector<std::string>{"convert " + f.path("data.csv") + " -o " + out,
                                "fit " + f.path("data.csv") + " -m lambert -o " + out, "rtable lambert -o " + out}) {
    ASSERT_EQ(run_cli(arguments).status, 0) << arguments;
    ASSERT_GT(fs::file_size(out), limit) << arguments << " writes too little to reach the limit";
    fs::remove(out);
    f.snapshot();
    const auto r = test::run_cli_with_file_size_limit(arguments);
    EXPECT_TRUE(refused_with(r, {out + ": " + test::kFileTooLarge})) << arguments;
    EXPECT_EQ(f.changes(), std::vector<std::string>{}) << arguments;
  }
}

TEST(CliDataLoss, FitToStandardOutputKeepsTheReportApart) {
  CaseFolder f = inputs("fit-stdout");
  const auto r = test::run_shell(test::cli_program() + " fit " + f.path("data.csv") + " -m lambert -o - 2>/dev/null");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.rfind("{", 0), 0u) << r.output;  // the fit file only: the ranking went to standard error
  EXPECT_NE(r.output.find("\"format\": \"roadbrdf-fit\""), std::string::npos);
}

TEST(CliDataLoss, OutputThroughASymbolicLinkKeepsTheLink) {
  CaseFolder f = inputs("symlink-output");
  f.write("target.csv", "old\n");
  fs::create_symlink("target.csv", f.path("link.csv"));
  const auto r = run_cli("convert " + f.path("data.csv") + " -o " + f.path("link.csv"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::is_symlink(f.path("link.csv")));
  std::ifstream in(f.path("target.csv"));
  std::string first;
  std::getline(in, first);
  EXPECT_EQ(first.rfind("# roadbrdf spectral BRDF dataset", 0), 0u) << first;
}

TEST(CliDataLoss, FifoOutputIsWrittenNotReplaced) {
  CaseFolder f = inputs("fifo-output");
  ASSERT_EQ(::mkfifo(f.path("pipe").c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] {
    std::ifstream in(f.path("pipe"));
    std::stringstream s;
    s << in.rdbuf();
    received = s.str();
  });
  const auto r = run_cli("convert " + f.path("data.csv") + " -o " + f.path("pipe"));
  reader.join();
  ASSERT_EQ(r.status, 0) << r.output;
  struct stat st {};
  ASSERT_EQ(::lstat(f.path("pipe").c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  EXPECT_NE(received.find("theta_i,phi_i,theta_r,phi_r,500"), std::string::npos) << received;
}

TEST(CliDataLoss, ReadOnlyOutputIsRefusedOrKeepsItsMode) {
  CaseFolder f = inputs("readonly-output");
  f.write("ro.csv", "precious\n");
  ASSERT_EQ(::chmod(f.path("ro.csv").c_str(), 0444), 0);
  const auto r = run_cli("convert " + f.path("data.csv") + " -o " + f.path("ro.csv"));
  struct stat st {};
  ASSERT_EQ(::stat(f.path("ro.csv").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0444u);
  if (::geteuid() != 0) {
    EXPECT_TRUE(refused_with(r, {f.path("ro.csv") + ": cannot write: Permission denied"}));
  } else {
    EXPECT_EQ(r.status, 0) << r.output;
  }
}

TEST(CliDataLoss, DirectoriesAreNotFiles) {
  CaseFolder f = inputs("directories");
  fs::create_directories(f.path("folder"));
  f.snapshot();
  for (const std::string& arguments : std::vector<std::string>{
           "convert " + f.path("folder"), "check " + f.path("folder"),
           "fit " + f.path("folder") + " -m lambert -o x.json", "eval lambert --geometry " + f.path("folder"),
           "albedo " + f.path("lambert.fit.json") + " --spectrum " + f.path("folder"),
           "convert " + f.path("folder") + " --from alta --wavelength 550",
           "rtable --import " + f.path("folder") + " --import-format rtb"}) {
    EXPECT_TRUE(refused_with(run_cli(arguments), {f.path("folder") + ": is a directory"})) << arguments;
  }
  EXPECT_TRUE(refused_with(run_cli("convert " + f.path("data.csv") + " -o " + f.path("folder")),
                           {f.path("folder") + ": is a directory"}));
  EXPECT_EQ(f.changes(), std::vector<std::string>{});
}

TEST(CliDataLoss, LongOutputNameWorks) {
  CaseFolder f = inputs("long-name");
  const std::string name = std::string(250, 'n') + ".csv";
  const auto r = run_cli("convert " + f.path("data.csv") + " -o " + f.path(name));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(f.path(name)));
  for (const auto& e : fs::directory_iterator(f.dir())) {
    EXPECT_NE(e.path().filename().string()[0], '.') << "temporary file left: " << e.path();
  }
}

TEST(CliDataLoss, StandardInputAndOutputAsDash) {
  CaseFolder f = inputs("dash");
  const auto r =
      test::run_shell("cat " + f.path("data.csv") + " | " + test::cli_program() + " convert - --to long -o - 2>&1");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("theta_i,phi_i,theta_r,phi_r,wavelength,brdf,sigma"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists("-"));
  const auto twice = run_cli("calibrate - --reference - --panel-reflectance x -o y");
  EXPECT_TRUE(refused_with(twice, {"standard input ('-') is given twice (SAMPLE and --reference)"}));
}

}  // namespace
}  // namespace roadbrdf
