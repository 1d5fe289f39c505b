// Adversarial command lines for every class of bad input beyond data loss (cli_data_loss_test.cpp):
// deeply nested and malformed JSON, float-to-int casts of untrusted numbers, parameters outside
// their declared bounds, silently accepted inputs, errors without a location. Every case asserts a
// clear message naming the file (and the key path or line where there is one), a non-zero exit
// that is neither an internal error nor a crash, no input modified and no temporary file left.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/case_folder.h"
#include "support/cli.h"
#include "support/paths.h"

namespace roadbrdf {
namespace {

using test::CaseFolder;
using test::refused_with;
using test::run_cli;

std::string lambert_fit(const std::string& albedo_values, const std::string& extra = "") {
  return R"({"format": "roadbrdf-fit", "version": 1, "best": "lambert", )" + extra +
         R"("fits": [{"model": "lambert", "options": {}, "wavelengths": [400, 500, 600],
            "parameters": {"albedo": )" +
         albedo_values + "}}]}";
}

const std::string kGrid = "theta_i,phi_i,theta_r,phi_r\n0,0,30,180\n30,0,0,0\n";
const std::string kCuretTable = "1 0.1 0.2 0.3 0.4\n2 0.5 0.6 0.7 0.8\n";  // CUReT table.txt, radians

std::string nested(std::size_t depth) { return std::string(depth, '[') + std::string(depth, ']'); }

struct Case {
  std::string name;           // names the case in failures
  std::string file, content;  // the input written into the case folder
  std::string arguments;      // command line; {} = the input's path, {out} = an output, {dir} = the case folder
  std::vector<std::string> fragments;  // expected in the message (besides the file name)
  bool names_file = true;              // false for errors in an option, not in the file
};

std::string substitute(std::string text, const std::string& placeholder, const std::string& value) {
  for (auto at = text.find(placeholder); at != std::string::npos; at = text.find(placeholder, at + value.size())) {
    text.replace(at, placeholder.size(), value);
  }
  return text;
}

// Runs every case in a fresh folder: refused, message naming the file and the fragments, no input
// modified and no file added (temporary outputs included).
void expect_refused(const std::vector<Case>& cases) {
  for (const Case& c : cases) {
    CaseFolder f("adversarial-" + c.name);
    const std::string input = f.write(c.file, c.content);
    f.write("grid.csv", kGrid);
    f.write("table.txt", kCuretTable);
    f.write("lambert.fit.json", lambert_fit("[0.2, 0.3, 0.4]"));
    f.snapshot();
    std::string arguments = substitute(c.arguments, "{out}", f.path("out.csv"));
    arguments = substitute(substitute(arguments, "{dir}", f.dir()), "{}", input);
    const auto r = run_cli(arguments);
    std::vector<std::string> fragments = c.fragments;
    if (c.names_file) fragments.push_back(c.file);
    EXPECT_TRUE(refused_with(r, fragments)) << c.name;
    EXPECT_EQ(f.changes(), std::vector<std::string>{}) << c.name;
  }
}

TEST(CliAdversarial, DeeplyNestedJsonIsRefusedAtTheDepthLimit) {
  const std::string deep = nested(200000);
  const std::string surface = R"({"format": "roadbrdf-surface", "version": 1, "extra": )" + deep + "}";
  expect_refused({
      {"fit-options",
       "deep.fit.json",
       lambert_fit("[0.2, 0.3, 0.4]", R"("junk": )" + deep + ", "),
       "rtable {} -o {out}",
       {"nested deeper than 64 levels", "junk"}},
      {"fit-in-options",
       "deep2.fit.json",
       R"({"format": "roadbrdf-fit", "fits": [{"model": "lambert", "options": )" + deep + "}]}",
       "rtable {} -o {out}",
       {"nested deeper than 64 levels", "fits[0].options"}},
      {"mix",
       "deep.mix.json",
       R"({"format": "roadbrdf-mix", "end_members": [{"options": )" + deep + "}]}",
       "rtable {} -o {out}",
       {"nested deeper than 64 levels", "end_members[0].options"}},
      {"formulation",
       "F.json",
       R"({"format": "roadbrdf-formulation", "components": )" + deep + "}",
       "mix {} -o {out}",
       {"nested deeper than 64 levels", "components"}},
      {"surface",
       "S.json",
       surface,
       "render {} --grid {dir}/grid.csv -o {out}",
       {"nested deeper than 64 levels", "extra"}},
  });
}

TEST(CliAdversarial, MalformedJsonNumbersKeysAndTypesNameTheKeyPath) {
  expect_refused({
      {"overflow",
       "big.fit.json",
       lambert_fit("[0.2, 1e400, 0.3]"),
       "rtable {} -o {out}",
       {":2:", "fits[0].parameters.albedo[1]", "number overflow"}},
      {"duplicate",
       "dup.fit.json",
       lambert_fit("[0.2, 0.3, 0.4]", R"("best": "lambert", )"),
       "rtable {} -o {out}",
       {"best: duplicate key", ":1:"}},
      {"type",
       "type.fit.json",
       lambert_fit("[0.2, \"x\", 0.4]"),
       "rtable {} -o {out}",
       {"fits[0].parameters.albedo[1]: must be a number, not string"}},
      {"syntax",
       "syntax.fit.json",
       "{\"format\": \"roadbrdf-fit\",\n \"fits\": [}",
       "rtable {} -o {out}",
       {":2:", "not valid JSON"}},
      {"unknown-model",
       "model.fit.json",
       R"({"format": "roadbrdf-fit", "best": "nope", "fits": [{"model": "nope", "wavelengths": [500],
          "parameters": {}}]})",
       "rtable {} -o {out}",
       {"fits[0].model", "nope"}},
      {"wavelength-order",
       "order.fit.json",
       R"({"format": "roadbrdf-fit", "best": "lambert", "fits": [{"model": "lambert", "wavelengths": [500, 400],
          "parameters": {"albedo": [0.2, 0.3]}}]})",
       "rtable {} -o {out}",
       {"fits[0].wavelengths[1]", "strictly increasing"}},
  });
}

TEST(CliAdversarial, ParametersOutsideTheirDeclaredBoundsAreRefused) {
  expect_refused({
      {"lambert",
       "neg.fit.json",
       lambert_fit("[0.2, -5, 0.3]"),
       "rtable {} -o {out}",
       {"fits[0].parameters.albedo[1]", "outside its bounds [0, 1]"}},
      {"oren-nayar",
       "on.fit.json",
       R"({"format": "roadbrdf-fit", "best": "oren-nayar", "fits": [{"model": "oren-nayar", "wavelengths": [500],
          "parameters": {"albedo": [0.3], "sigma": [50]}}]})",
       "rtable {} -o {out}",
       {"fits[0].parameters.sigma[0]", "outside its bounds"}},
      {"hapke",
       "hapke.fit.json",
       R"({"format": "roadbrdf-fit", "best": "hapke", "fits": [{"model": "hapke", "wavelengths": [500],
          "parameters": {"w": [-3], "b": [0.3], "c": [0.5], "B0": [0.5], "h": [0.1], "theta_bar": [0.2]}}]})",
       "rtable {} -o {out}",
       {"fits[0].parameters.", "outside its bounds"}},
  });
}

TEST(CliAdversarial, BadIntegersInSurfaceAndFormulationFilesAreRefused) {
  const std::string surface_head = R"({"format": "roadbrdf-surface", "cell_size_mm": 1, "periodic": true, )";
  const std::string surface_tail =
      R"("heights_mm": [0, 0, 0, 0], "materials": [{"name": "a", "model": "lambert", "parameters": {"albedo": 0.3}}]})";
  const std::string formulation_tail = R"(, "name": "T", "components": [{"name": "G", "kind": "binder",
      "mass_percent": 100, "density_g_cm3": 1.0, "fit": "lambert.fit.json"}]})";
  expect_refused({
      {"nx",
       "nx.json",
       surface_head + R"("version": 1, "nx": 1e10, "ny": 2, "material": [0, 0, 0, 0], )" + surface_tail,
       "render {} --grid {dir}/grid.csv -o {out}",
       {"nx: must be an integer in [2, 2147483647], got 10000000000"}},
      {"version",
       "version.json",
       surface_head + R"("version": 1.9, "nx": 2, "ny": 2, "material": [0, 0, 0, 0], )" + surface_tail,
       "render {} --grid {dir}/grid.csv -o {out}",
       {"version: must be an integer in [1, 1], got 1.9"}},
      {"material",
       "material.json",
       surface_head + R"("version": 1, "nx": 2, "ny": 2, "material": [0, 65536, 0, 0], )" + surface_tail,
       "render {} --grid {dir}/grid.csv -o {out}",
       {"material[1]: must be an integer in [0, 0], got 65536"}},
      {"formulation-version",
       "F.json",
       R"({"format": "roadbrdf-formulation", "version": 4294967297)" + formulation_tail,
       "mix {} -o {out}",
       {"version: must be 1"}},
  });
}

TEST(CliAdversarial, UntrustedNumbersAreRangeAndIntegralityChecked) {
  const std::string data =
      "theta_i,phi_i,theta_r,phi_r,500,600\n0,0,30,180,0.1,0.2\n30,0,0,0,0.1,0.2\n"
      "30,0,30,180,0.12,0.2\n45,0,30,0,0.1,0.2\n";
  expect_refused({
      {"curet-huge",
       "abrdf.dat",
       "1e10 0.1 0.2\n",
       "convert {} --from curet --curet-table {dir}/table.txt --sample 1 -o {out}",
       {"abrdf.dat:1:1", "sample number '1e10' is not an integer >= 1"}},
      {"curet-fraction",
       "abrdf.dat",
       "1 0.1 0.2\n1.7 0.1 0.2\n",
       "convert {} --from curet --curet-table {dir}/table.txt --sample 1 -o {out}",
       {"abrdf.dat:2:1", "sample number '1.7'"}},
      {"curet-wavelength",
       "abrdf.dat",
       "1 0.1 0.2\n",
       "convert {} --from curet --curet-table {dir}/table.txt --sample 1 --wavelength -5 -o {out}",
       {"--wavelength -5 nm: must be finite and > 0"},
       false},
      {"check-tolerance",
       "data.csv",
       data,
       "check {} --tolerance 1e-310",
       {"angle tolerance must be in [1e-6, 90] deg"},
       false},
      {"check-neighbours", "data.csv", data, "check {} --neighbours -5", {"neighbours must be >= 2"}, false},
      {"flat-size",
       "unused.txt",
       "",
       "surface lambert -p albedo=0.3 --flat --size nanmm -o {out}",
       {"--size: expected a length such as 60mm, got 'nanmm'"},
       false},
  });
}

TEST(CliAdversarial, AtmosphereDayIsAWholeDayOfTheYear) {
  for (const std::string day : {"1e10", "81.9", "0", "367"}) {
    CaseFolder f("adversarial-day-" + day);
    f.snapshot();
    const auto r = run_cli("albedo lambert -p albedo=0.3 --atmosphere spectrl2:day=" + day + " -o " + f.path("a.csv"));
    EXPECT_TRUE(refused_with(r, {"day = '" + day + "' must be an integer day of year in 1..366"})) << day;
    EXPECT_EQ(f.changes(), std::vector<std::string>{}) << day;
  }
}

TEST(CliAdversarial, SolarSpectrumFilesAreReadWhole) {
  expect_refused({
      {"typo",
       "solar.csv",
       "wavelength,irradiance\n4OO,1\n500,1.2\n600,1\n",
       "albedo {dir}/lambert.fit.json --spectrum {} -o {out}",
       {"solar.csv:2:1", "4OO"}},
      {"negative",
       "solar.csv",
       "400,1\n500,-1.2\n600,1\n",
       "albedo {dir}/lambert.fit.json --spectrum {} -o {out}",
       {"solar.csv:2:5", "negative irradiance '-1.2'"}},
      {"huge",
       "solar.csv",
       "400,1e308\n500,1e308\n600,1e308\n",
       "albedo {dir}/lambert.fit.json --spectrum {} -o {out}",
       {"must be finite and > 0"}},
  });
}

TEST(CliAdversarial, AltaHeadersAreStrict) {
  const std::string head = "#DIM 3 1\n#PARAM_IN ISOTROPIC_TL_TV_PROJ_DPHI\n#PARAM_OUT INV_STERADIAN\n";
  expect_refused({
      {"dim-junk",
       "a.alta",
       "#DIM 4 1junk\n",
       "convert {} --from alta --wavelength 550 -o {out}",
       {"a.alta:1:8", "#DIM count '1junk'"}},
      {"late-param",
       "a.alta",
       head + "0.1 0.2 0.3 0.5\n#PARAM_IN SPHERICAL_TL_PL_TV_PV\n0.1 0.2 0.3 0.4 0.5\n",
       "convert {} --from alta --wavelength 550 -o {out}",
       {"a.alta:5:2", "#PARAM_IN after the data"}},
  });
  // "#  PARAM_IN" with spaces after '#' is the same header line.
  CaseFolder f("adversarial-alta-spaces");
  const std::string in = f.write("a.alta",
                                 "#  DIM 3 1\n#  PARAM_IN ISOTROPIC_TL_TV_PROJ_DPHI\n#  PARAM_OUT INV_STERADIAN\n"
                                 "0.1 0.2 0.3 0.5\n0.2 0.1 0.1 0.4\n");
  const auto r = run_cli("convert " + in + " --from alta --wavelength 550 -o " + f.path("out.csv"));
  EXPECT_EQ(r.status, 0) << r.output;
}

TEST(CliAdversarial, SilentlyAcceptedInputsAreRefused) {
  CaseFolder grids("adversarial-rtable-alpha");
  const std::string table = grids.path("r.csv");
  ASSERT_EQ(run_cli("rtable lambert -p albedo=0.3 -o " + table).status, 0);
  std::string text;
  {
    std::ifstream in(table);
    std::stringstream s;
    s << in.rdbuf();
    text = s.str();
  }
  const auto alpha_at = text.find("alpha_deg = ");
  ASSERT_NE(alpha_at, std::string::npos);
  auto with_alpha = [&](const std::string& a) {
    std::string t = text;
    t.replace(alpha_at, t.find('\n', alpha_at) - alpha_at, "alpha_deg = " + a);
    return t;
  };
  expect_refused({
      {"alpha-junk", "r.csv", with_alpha("1abc"), "rtable --import {} -o {out}", {":3:", "alpha_deg = '1abc'"}},
      {"alpha-negative", "r.csv", with_alpha("-7"), "rtable --import {} -o {out}", {":3:", "alpha_deg = '-7'"}},
  });
}

// "+0" is a number like "+0.1"; a --spectrum that cannot matter is still read (a typo is an error), and a
// free comment line survives convert.
TEST(CliAdversarial, PlusZeroSpectrumAndCommentsAreNotIgnored) {
  CaseFolder f("adversarial-plus-zero");
  auto r = run_cli("albedo lambert -p albedo=0.3 --sun-zenith +0 -o " + f.path("a.csv"));
  EXPECT_EQ(r.status, 0) << r.output;
  r = run_cli("albedo lambert -p albedo=0.3 --spectrum " + f.path("missing.csv") + " -o " + f.path("b.csv"));
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("missing.csv"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(f.path("b.csv")));
  const std::string in = f.path("in.csv");
  std::ofstream(in) << "# operator J.D., lamp warmed up 20 min\ntheta_i,phi_i,theta_r,phi_r,500\n+0,0,10,0,0.1\n";
  r = run_cli("convert " + in + " -o " + f.path("out.csv"));
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream out(f.path("out.csv"));
  std::stringstream text;
  text << out.rdbuf();
  EXPECT_NE(text.str().find("\n# operator J.D., lamp warmed up 20 min\n"), std::string::npos) << text.str();
}

TEST(CliAdversarial, EvalRefusesItsOwnOutputAsGeometry) {
  CaseFolder f("adversarial-eval-twice");
  const std::string grid = f.write("g.csv", "theta_i,phi_i,theta_r,phi_r\n0,0,30,180\n30,0,0,0\n");
  ASSERT_EQ(run_cli("eval lambert -p albedo=0.3 --geometry " + grid + " -o " + f.path("e.csv")).status, 0);
  f.snapshot();
  const auto r = run_cli("eval lambert -p albedo=0.3 --geometry " + f.path("e.csv") + " -o " + f.path("e2.csv"));
  EXPECT_TRUE(refused_with(r, {"e.csv", "already has a 'brdf' column"}));
  EXPECT_EQ(f.changes(), std::vector<std::string>{});
}

TEST(CliAdversarial, GeometryErrorsPointAtTheirOwnCell) {
  expect_refused({
      {"theta-r",
       "g.csv",
       "theta_i,phi_i,theta_r,phi_r\n0,0,30,180\n10,0,95,0\n",
       "eval lambert -p albedo=0.3 --geometry {} -o {out}",
       {"g.csv:3:6", "theta_r = 95 deg is outside [0, 90] deg"}},
      {"road-alpha",
       "g.csv",
       "gamma,alpha,beta,delta\n0,1,0,0\n10,-5,0,0\n",
       "eval lambert -p albedo=0.3 --geometry {} -o {out}",
       {"g.csv:3:4", "alpha = -5 deg"}},
  });
}

TEST(CliAdversarial, NonUtf8FileNamesAreReportedNotCrashed) {
  CaseFolder f("adversarial-utf8");
  const std::string bad = f.path("bad\xff.csv");
  f.write("bad\xff.csv", "theta_i,phi_i,theta_r,phi_r,brdf_500\n0,0,30,180,0.1\n30,0,0,0,0.1\n");
  f.snapshot();
  const auto r = run_cli("check '" + bad + "' --json");
  EXPECT_NE(r.status, 3) << r.output;
  EXPECT_LT(r.status, 128) << r.output;
  EXPECT_EQ(f.changes(), std::vector<std::string>{});
}

// A .sig row that is only carriage returns is a blank line (it crashed the reader), and a .sed
// channel count beyond any integer is refused (it was an undefined float-to-integer cast).
TEST(CliAdversarial, InstrumentFilesWithCarriageReturnLinesOrHugeChannelCounts) {
  CaseFolder f("instrument-blanks");
  const std::string sig = f.copy(test::instrument_files_dir() + "/sig_no_overlap.sig", "plain.sig");
  std::ifstream in(sig, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  f.write("cr.sig", text.str() + "\r\r\n");
  const std::string geometry = " --geometry gamma=0,alpha=45,beta=0,delta=0 -o ";
  const auto plain = run_cli("convert " + sig + geometry + f.path("plain.csv"));
  ASSERT_EQ(plain.status, 0) << plain.output;
  const auto cr = run_cli("convert " + f.path("cr.sig") + geometry + f.path("cr.csv"));
  ASSERT_EQ(cr.status, 0) << cr.output;
  std::ifstream a(f.path("plain.csv")), b(f.path("cr.csv"));
  std::stringstream plain_csv, cr_csv;
  plain_csv << a.rdbuf();
  cr_csv << b.rdbuf();
  // The same spectrum; only the file name in the metadata differs.
  EXPECT_EQ(substitute(cr_csv.str(), "cr.sig", "plain.sig"), plain_csv.str());
  expect_refused({{"sed-channels",
                   "huge.sed",
                   "Version: 2.3\nChannels: 1e30\nData:\nWvl\tReflect. %\n400\t50\n",
                   "convert {} --geometry gamma=0,alpha=45,beta=0,delta=0 -o {out}",
                   {"huge.sed:2", "'Channels: 1e30' is more than the 1000000 channels"}}});
}

// Endless, huge or non-regular inputs are refused with a message, in bounded time and memory. Each
// command runs under `timeout`, so that a regression fails instead of hanging.
TEST(CliAdversarial, EndlessHugeAndNonRegularInputsAreRefused) {
  CaseFolder f("unbounded-reads");
  const std::string dir = test::instrument_files_dir();
  for (const std::string name : {"run_001.asd", "run_white.asd", "run_dark.asd", "rho.txt"}) {
    f.copy(dir + "/" + name, name);
  }
  auto manifest = [&](const std::string& file, const std::string& white) {
    return f.write(file, "file,role,gamma,alpha,beta,delta\n" + white + ",white,,,,\nrun_001.asd,sample,0,45,0,0\n");
  };
  manifest("run.csv", "run_white.asd");
  manifest("fifo_entry.csv", "entry.fifo");
  for (const std::string fifo : {"entry.fifo", "manifest.fifo", "panel.fifo"}) {
    ASSERT_EQ(::mkfifo(f.path(fifo).c_str(), 0600), 0);
  }
  // Outside the case folder, whose snapshot would read it.
  const std::string sparse = test::scratch_path("sparse-3GiB.asd");
  std::ofstream(sparse) << "as7";
  std::filesystem::resize_file(sparse, std::uintmax_t{3} << 30);
  f.snapshot();
  const std::string calibrate = "timeout 60 " + test::cli_program() + " calibrate --manifest ";
  struct Case {
    std::string command;
    std::vector<std::string> fragments;
  };
  const std::vector<Case> cases = {
      {"timeout 60 " + test::cli_program() + " check /dev/zero",
       {"/dev/zero:1: line longer than 67108864 bytes (64 MiB) without a line end"}},
      {calibrate + f.path("manifest.fifo") + " --panel-reflectance " + f.path("rho.txt") + " -o " + f.path("o.csv"),
       {"manifest.fifo", "is a FIFO (named pipe), not a regular file: a run manifest must be a regular file"}},
      {calibrate + f.path("fifo_entry.csv") + " --panel-reflectance " + f.path("rho.txt") + " -o " + f.path("o.csv"),
       {"entry.fifo", "is a FIFO (named pipe), not a regular file: an instrument file (.asd, .sed, .sig) must be"}},
      {calibrate + f.path("run.csv") + " --panel-reflectance " + f.path("panel.fifo") + " -o " + f.path("o.csv"),
       {"panel.fifo", "a panel reflectance file must be a regular file"}},
      {"timeout 60 " + test::cli_program() + " convert " + sparse + " --geometry gamma=0,alpha=45,beta=0,delta=0 -o " +
           f.path("o.csv"),
       {"sparse-3GiB.asd", "file is 3221225472 bytes (3 GiB), more than the 16777216 bytes (16 MiB)"}},
  };
  for (const Case& c : cases) {
    const auto r = test::run_shell(c.command + " 2>&1");
    EXPECT_TRUE(refused_with(r, c.fragments)) << c.command;
    EXPECT_EQ(f.changes(), std::vector<std::string>{}) << c.command;
  }
  std::filesystem::remove(sparse);
}

// Counts beyond what memory and time allow are refused by the library's request, named by their flag.
TEST(CliAdversarial, RequestCountsBeyondTheirLimitsAreRefused) {
  CaseFolder f("request-counts");
  f.copy(test::test_data_dir() + "/io/wide_small.csv", "data.csv");
  ASSERT_EQ(run_cli("surface lambert --flat -o " + f.path("flat.json")).status, 0);
  f.snapshot();
  auto r = run_cli("render " + f.path("flat.json") + " --albedo 30 --samples 99999999999 -o " + f.path("a.csv"));
  EXPECT_TRUE(refused_with(r, {"--samples: 99999999999 is above the limit of 1073741824 paths per geometry"}));
  r = run_cli("fit " + f.path("data.csv") + " -m lambert --multistart 1000000000 -o " + f.path("fit.json"));
  EXPECT_TRUE(refused_with(r, {"--multistart: 1000000000 is outside [1, 10000]"}));
  EXPECT_EQ(f.changes(), std::vector<std::string>{});
}

}  // namespace
}  // namespace roadbrdf
