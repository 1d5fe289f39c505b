// Files as people write them: every dialect reads to the same dataset as the
// canonical CSV; the dialect is detected from the header line, --delimiter/--decimal override it,
// ambiguous or contradictory files are errors that name the options. Long files are checked for
// shape before the table is allocated.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/io/dataset_dialect.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/geometry_file.h"
#include "support/cli.h"
#include "support/scratch.h"

namespace {

using namespace roadbrdf;

const test::ScratchDirectory& scratch() {
  static const test::ScratchDirectory dir;
  return dir;
}

std::string write_file(const std::string& name, const std::string& content) {
  const std::string p = (scratch().path() / name).string();
  std::ofstream(p, std::ios::binary) << content;
  return p;
}

DatasetReadOptions quiet() {
  DatasetReadOptions o;
  o.warn = [](const std::string&) {};
  return o;
}

// The canonical file: wide, ',' and '.', with uncertainties.
const std::string kCanonical =
    "# sample: asphalt\n"
    "theta_i,phi_i,theta_r,phi_r,450,550.5,sigma_450,sigma_550.5\n"
    "0,0,30,180,0.0125,0.025,0.001,0.002\n"
    "30,0,45.5,180,0.0375,-0.0005,0.003,0.004\n"
    "60,0,10,90,0.125,1.5e-3,0.005,0.006\n";

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t k = s.find(from); k != std::string::npos; k = s.find(from, k + to.size()))
    s.replace(k, from.size(), to);
  return s;
}

// A spreadsheet export: ';' between cells, ',' in numbers.
std::string semicolon_decimal_comma(const std::string& canonical) {
  std::string s;
  for (char c : canonical) s += c == ',' ? ';' : c == '.' ? ',' : c;
  return s;
}

void expect_same(const SpectralDataset& a, const SpectralDataset& b) {
  ASSERT_EQ(a.wavelengths, b.wavelengths);
  ASSERT_EQ(a.geometries.size(), b.geometries.size());
  for (std::size_t k = 0; k < a.geometries.size(); ++k) {
    EXPECT_EQ(a.geometries[k].theta_i, b.geometries[k].theta_i);
    EXPECT_EQ(a.geometries[k].phi_i, b.geometries[k].phi_i);
    EXPECT_EQ(a.geometries[k].theta_r, b.geometries[k].theta_r);
    EXPECT_EQ(a.geometries[k].phi_r, b.geometries[k].phi_r);
  }
  EXPECT_EQ(a.brdf, b.brdf);
  EXPECT_EQ(a.sigma, b.sigma);
  EXPECT_EQ(a.metadata, b.metadata);
  EXPECT_EQ(a.convention, b.convention);
}

std::string error_of(const std::string& path, const DatasetReadOptions& o = quiet()) {
  try {
    read_dataset(path, o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(DatasetDialect, EveryDialectReadsLikeTheCanonicalFile) {
  const SpectralDataset reference = read_dataset(write_file("canonical.csv", kCanonical), quiet());
  ASSERT_EQ(reference.brdf[3], -0.0005);  // the numbers as written (not a value of the code)
  const std::string header_variants =
      replace_all(kCanonical, "theta_i,phi_i,theta_r,phi_r,450,550.5,sigma_450,sigma_550.5",
                  " Theta_I [deg] ,PHI_in, thetaV (deg),Phi_R_deg, 450nm,550.5 nm,SIGMA_450,sigma_550.5nm");
  const struct {
    const char* name;
    std::string content;
  } variants[] = {
      {"semicolon.csv", semicolon_decimal_comma(kCanonical)},
      {"semicolon_point.csv", replace_all(kCanonical, ",", ";")},
      {"tab.tsv", replace_all(kCanonical, ",", "\t")},
      {"bom_crlf.csv", "\xEF\xBB\xBF" + replace_all(kCanonical, "\n", "\r\n")},
      {"spaces.csv", replace_all(kCanonical, ",", " , ")},
      {"header.csv", header_variants},
      {"everything.csv", "\xEF\xBB\xBF" + replace_all(semicolon_decimal_comma(header_variants), "\n", "\r\n")},
  };
  for (const auto& v : variants) {
    SCOPED_TRACE(v.name);
    expect_same(read_dataset(write_file(v.name, v.content), quiet()), reference);
  }
}

TEST(DatasetDialect, LongFilesToo) {
  const std::string canonical =
      "theta_i,phi_i,theta_r,phi_r,wavelength,brdf\n0,0,30,180,450,0.5\n0,0,30,180,550.5,0.25\n"
      "30,0,10,0,450,0.125\n30,0,10,0,550.5,0.0625\n";
  const SpectralDataset reference = read_dataset(write_file("long.csv", canonical), quiet());
  const std::string dialect =
      "\xEF\xBB\xBF" +
      replace_all(semicolon_decimal_comma(replace_all(canonical, "wavelength,brdf", "Lambda , BRDF")), "\n", "\r\n");
  expect_same(read_dataset(write_file("long_semicolon.csv", dialect), quiet()), reference);
}

TEST(DatasetDialect, OverridesAndTheirValidation) {
  const std::string path = write_file("sc.csv", semicolon_decimal_comma(kCanonical));
  DatasetReadOptions o = quiet();
  o.delimiter = ';';
  o.decimal = ',';
  EXPECT_EQ(read_dataset(path, o).brdf[3], -0.0005);
  o.decimal = '.';
  const std::string e = error_of(path, o);
  // Header: "550,5" is no wavelength with a decimal point.
  EXPECT_NE(e.find("sc.csv:2:"), std::string::npos) << e;
  // The library names the field (core/error.h); the command line shows its flag (below).
  EXPECT_NE(e.find("see `decimal`"), std::string::npos) << e;
  o.delimiter = ',';
  o.decimal = ',';
  EXPECT_THROW(validate_read_options(o), InputError);
  EXPECT_EQ(delimiter_from_name("tab"), '\t');
  EXPECT_EQ(delimiter_from_name("auto"), 0);
  try {
    delimiter_from_name("|");
    ADD_FAILURE() << "'|' accepted as a delimiter";
  } catch (const FieldError& e) {
    EXPECT_EQ(e.field(), "delimiter");
  }
  try {
    decimal_from_name(";", "data_read.decimal");
    ADD_FAILURE() << "';' accepted as a decimal separator";
  } catch (const FieldError& e) {
    EXPECT_EQ(e.field(), "data_read.decimal");
  }
}

TEST(DatasetDialect, AmbiguousHeaderNamesTheOptions) {
  const std::string path = write_file("ambiguous.csv", "theta_i,phi_i,theta_r,phi_r;500\n0,0,0,0;0.1\n");
  const std::string e = error_of(path);
  EXPECT_NE(e.find("ambiguous.csv:1: cannot tell the delimiter"), std::string::npos) << e;
  EXPECT_NE(e.find("`delimiter`"), std::string::npos) << e;
  EXPECT_NE(e.find("`decimal`"), std::string::npos) << e;
}

TEST(DatasetDialect, ContradictoryDecimalSeparatorsNameBothPlaces) {
  const std::string path =
      write_file("mixed.csv", "theta_i;phi_i;theta_r;phi_r;500;600\n0;0;30;180;0,1;0,2\n30;0;30;180;0.3;0,4\n");
  const std::string e = error_of(path);
  EXPECT_NE(e.find("mixed.csv:3:13: '0.3'"), std::string::npos) << e;
  EXPECT_NE(e.find("line 2 column 12 used ','"), std::string::npos) << e;
  EXPECT_NE(e.find("`decimal`"), std::string::npos) << e;
}

TEST(DatasetDialect, AnglesInRadiansAreRefused) {
  const std::string path = write_file("rad.csv", "theta_i [rad],phi_i,theta_r,phi_r,500\n0,0,0.5,0,0.1\n");
  const std::string e = error_of(path);
  EXPECT_NE(e.find("rad.csv:1:1: column 'theta_i [rad]' is in radians"), std::string::npos) << e;
}

TEST(DatasetDialect, AnAliasAndItsCanonicalNameTogetherAreAnError) {
  const std::string path = write_file("twice.csv", "theta_i,phi_i,theta_r,phi_r,inc,500\n0,0,0,0,0,0.1\n");
  const std::string e = error_of(path);
  EXPECT_NE(e.find("twice.csv:1:"), std::string::npos) << e;
  EXPECT_NE(e.find("second 'theta_i' column"), std::string::npos) << e;
}

TEST(DatasetDialect, GeometryTablesAcceptTheSameHeaderNames) {
  const std::string path = write_file("grid.csv", "Theta_i (deg),PHI_I,view,phi_r\n30,0,45,180\n");
  const GeometryTable t = read_geometry_file(path);
  ASSERT_EQ(t.geometries.size(), 1u);
  EXPECT_NEAR(t.geometries[0].theta_r, 45.0 * 3.14159265358979323846 / 180.0, 1e-15);
}

TEST(DatasetDialect, ErrorsKeepFileLineAndColumn) {
  const std::string e1 = error_of(write_file("bad.csv", "theta_i,phi_i,theta_r,phi_r,500\n0,0,30,180,abc\n"));
  EXPECT_NE(e1.find("bad.csv:2:12: 'abc' is not a BRDF value"), std::string::npos) << e1;
  const std::string e2 = error_of(write_file("bad2.tsv", "theta_i\tphi_i\ttheta_r\tphi_r\t500\n0\t0\t95\t180\t0.1\n"));
  EXPECT_NE(e2.find("bad2.tsv:2:5: theta_r = '95' is outside [0, 90] deg"), std::string::npos) << e2;
  const std::string e3 = error_of(write_file("bad3.csv", "theta_i,phi_i,theta_r,phi_r,500\n0,0,30,180,0.1,0.2\n"));
  EXPECT_NE(e3.find("bad3.csv:2:16: row has 6 cells but the header has 5 columns (extra cell '0.2')"),
            std::string::npos)
      << e3;
}

TEST(LongShape, SparseLongFileIsRefusedBeforeAllocatingTheTable) {
  // 20000 rows, each a new geometry at a new wavelength: 20000 x 20000 cells would be 3.2 GB per
  // array; the shape check refuses it from the records alone.
  std::ostringstream s;
  s << "theta_i,phi_i,theta_r,phi_r,wavelength,brdf\n";
  for (int k = 0; k < 20000; ++k) s << "10," << k % 360 << ',' << 1 + k / 360 << ",0," << 400 + k << ",0.1\n";
  const std::string e = error_of(write_file("sparse.csv", s.str()));
  EXPECT_NE(e.find("sparse.csv:2: the geometry first given on this line has no value at wavelength 401 nm"),
            std::string::npos)
      << e;
}

TEST(LongShape, AnAbsentRowIsAMissingCellCountedAndWarned) {
  // Three geometries x two wavelengths, the second geometry's 600 nm row never written: that cell
  // reads as missing, exactly as if its row had an empty brdf cell.
  const std::string absent =
      "theta_i,phi_i,theta_r,phi_r,wavelength,brdf\n0,0,30,180,500,0.1\n0,0,30,180,600,0.2\n"
      "10,0,30,180,500,0.3\n20,0,30,180,500,0.5\n20,0,30,180,600,0.6\n";
  const std::string empty_cell =
      "theta_i,phi_i,theta_r,phi_r,wavelength,brdf\n0,0,30,180,500,0.1\n0,0,30,180,600,0.2\n"
      "10,0,30,180,500,0.3\n10,0,30,180,600,\n20,0,30,180,500,0.5\n20,0,30,180,600,0.6\n";
  std::vector<std::string> warnings;
  DatasetReadOptions o;
  o.warn = [&](const std::string& w) { warnings.push_back(w); };
  DatasetReadStats stats;
  const SpectralDataset a = read_dataset(write_file("absent.csv", absent), o, stats);
  const SpectralDataset b = read_dataset(write_file("empty_cell.csv", empty_cell), quiet());
  ASSERT_EQ(a.geometries.size(), 3u);
  ASSERT_EQ(a.wavelengths, (std::vector<double>{500.0, 600.0}));
  EXPECT_TRUE(std::isnan(a.brdf[3]));
  for (std::size_t k : {0u, 1u, 2u, 4u, 5u}) EXPECT_EQ(a.brdf[k], b.brdf[k]) << k;
  EXPECT_EQ(missing_value_count(a), 1u);
  EXPECT_EQ(stats.absent_rows, 1u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("1 (geometry, wavelength) pairs of 6 have no row (kept as missing NaN cells; first: the "
                             "geometry of "),
            std::string::npos)
      << warnings[0];
  EXPECT_NE(warnings[0].find("absent.csv:4 at 600 nm"), std::string::npos) << warnings[0];
  // Refusing missing values refuses the absent row, at the line of its geometry.
  DatasetReadOptions strict = quiet();
  strict.allow_missing = false;
  try {
    read_dataset(write_file("absent_strict.csv", absent), strict);
    ADD_FAILURE() << "an absent row was accepted with allow_missing = false";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("absent_strict.csv:4: the geometry first given on this line has no value at "
                                         "wavelength 600 nm (missing values are refused here)"),
              std::string::npos)
        << e.what();
  }
}

TEST(LongShape, DuplicatesAreReportedAtTheirFirstRepetitionInFileOrder) {
  const std::string path =
      write_file("dup.csv",
                 "theta_i,phi_i,theta_r,phi_r,wavelength,brdf\n0,0,30,0,600,1\n0,0,30,0,500,1\n10,0,30,0,500,1\n"
                 "10,0,30,0,600,1\n10,0,30,0,500,2\n0,0,30,0,600,3\n");
  const std::string e = error_of(path);
  EXPECT_NE(e.find("dup.csv:6:1: duplicate value: this geometry already has wavelength 500 nm at line 4"),
            std::string::npos)
      << e;
}

TEST(HugeLines, AnOverlongRowCostsOnlyItself) {
  std::string row = "0,0,30,180,0.1";
  row.reserve(4u << 20);
  while (row.size() < (4u << 20)) row += ",0.1";
  const std::string e = error_of(write_file("long_row.csv", "theta_i,phi_i,theta_r,phi_r,500\n" + row + "\n"));
  EXPECT_NE(e.find("long_row.csv:2:16: row has"), std::string::npos) << e;
  EXPECT_NE(e.find("but the header has 5 columns (extra cell '0.1')"), std::string::npos) << e;
}

TEST(DialectCli, CommandsAndPythonOfferTheSameOptions) {
  const std::string path = write_file("cli.csv", semicolon_decimal_comma(kCanonical));
  for (const std::string command : {"check", "convert", "fit", "resample"}) {
    std::string arguments = command + " " + path + " --delimiter ';' --decimal ,";
    if (command == "fit") arguments += " -m lambert -o " + (scratch().path() / "f.json").string();
    if (command == "resample") arguments += " --wavelengths 450:550:50";
    const auto r = test::run_cli(arguments);
    EXPECT_EQ(r.status, 0) << arguments << "\n" << r.output;
  }
  const auto bad = test::run_cli("check " + path + " --delimiter , --decimal ,");
  EXPECT_NE(bad.status, 0);
  EXPECT_NE(bad.output.find("a decimal comma needs another delimiter"), std::string::npos) << bad.output;
  const auto unknown = test::run_cli("fit " + path + " -m lambert --delimiter pipe -o -");
  EXPECT_NE(unknown.status, 0);
  EXPECT_NE(unknown.output.find("roadbrdf: error: --delimiter: 'pipe' is not one of auto"), std::string::npos)
      << unknown.output;
  const auto ambiguous_decimal = test::run_cli("check " + path + " --decimal .");
  EXPECT_NE(ambiguous_decimal.status, 0);
  EXPECT_NE(ambiguous_decimal.output.find("see --decimal)"), std::string::npos) << ambiguous_decimal.output;
}

}  // namespace
