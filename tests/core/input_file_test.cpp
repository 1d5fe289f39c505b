// InputFile and CsvReader (core/input_file.h, core/csv.h): read errors are errors, never a silent
// end of file; lines of any length; standard input as "-".
#include "roadbrdf/core/input_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/error.h"
#include "support/scratch.h"

namespace roadbrdf {
namespace {

namespace fs = std::filesystem;

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(InputFile, DirectoryIsAnErrorNotAnEmptyFile) {
  const std::string dir = test::scratch_path("a-directory");
  fs::create_directories(dir);
  const std::string message = error_of([&] { InputFile in(dir); });
  EXPECT_EQ(message, dir + ": is a directory, not a file");
  EXPECT_EQ(error_of([&] { CsvReader reader(dir); }), message);
}

TEST(InputFile, MissingFileNamesTheReason) {
  const std::string path = test::scratch_path("does-not-exist.csv");
  EXPECT_EQ(error_of([&] { InputFile in(path); }), path + ": cannot open file for reading: No such file or directory");
}

TEST(InputFile, ReadErrorIsAnError) {
  // Reading /proc/self/mem from offset 0 fails with EIO (the page is not mapped): a genuine read
  // error, which must not look like the end of the file.
  if (!fs::exists("/proc/self/mem")) GTEST_SKIP() << "no /proc";
  const std::string message = error_of([] {
    InputFile in("/proc/self/mem");
    std::string line;
    while (in.read_line(line)) {
    }
  });
  EXPECT_EQ(message, "/proc/self/mem:1: read error: Input/output error");
}

TEST(InputFile, LinesOfAnyLengthAndNoFinalNewline) {
  const std::string path = test::scratch_path("lines.txt");
  const std::string long_line(300000, 'x');
  std::ofstream(path) << "a\r\n" << long_line << "\n\nlast";
  InputFile in(path);
  std::string line;
  ASSERT_TRUE(in.read_line(line));
  EXPECT_EQ(line, "a\r");
  ASSERT_TRUE(in.read_line(line));
  EXPECT_EQ(line, long_line);
  ASSERT_TRUE(in.read_line(line));
  EXPECT_EQ(line, "");
  ASSERT_TRUE(in.read_line(line));
  EXPECT_EQ(line, "last");
  EXPECT_EQ(in.line_number(), 4);
  EXPECT_FALSE(in.read_line(line));
}

// Lines of every length around the 64 kB block (and far beyond it) are read as views into the
// buffer; each must equal what std::getline reads from the same file.
TEST(InputFile, ViewsAcrossBlockBoundariesEqualGetline) {
  const std::string path = test::scratch_path("views.txt");
  {
    std::ofstream out(path, std::ios::binary);
    unsigned state = 12345;
    for (int k = 0; k < 400; ++k) {
      state = state * 1103515245u + 12345u;
      const std::size_t length = k % 50 == 7 ? 200000 + k : (state >> 8) % 70000;
      out << std::string(length, static_cast<char>('a' + k % 26)) << (k % 3 == 0 ? "\r\n" : "\n");
    }
    out << "tail";
  }
  std::ifstream reference(path, std::ios::binary);
  InputFile in(path);
  std::string_view view;
  std::string expected;
  long lines = 0;
  while (std::getline(reference, expected)) {
    ASSERT_TRUE(in.read_line(view)) << "line " << lines + 1;
    ASSERT_EQ(view, expected) << "line " << lines + 1;
    ++lines;
  }
  EXPECT_EQ(lines, 401);
  EXPECT_EQ(in.line_number(), 401);
  EXPECT_FALSE(in.read_line(view));
  EXPECT_FALSE(in.read_line(view));
}

TEST(InputFile, EmptyFileAndLoneNewline) {
  const std::string empty = test::scratch_path("empty.txt");
  std::ofstream(empty) << "";
  InputFile a(empty);
  std::string_view view;
  EXPECT_FALSE(a.read_line(view));
  EXPECT_EQ(a.line_number(), 0);
  const std::string newline = test::scratch_path("newline.txt");
  std::ofstream(newline) << "\n";
  InputFile b(newline);
  ASSERT_TRUE(b.read_line(view));
  EXPECT_EQ(view, "");
  EXPECT_FALSE(b.read_line(view));
  EXPECT_EQ(b.line_number(), 1);
}

TEST(InputFile, ReadAllAfterSomeLines) {
  const std::string path = test::scratch_path("all.txt");
  std::ofstream(path) << "head\nrest of\nthe file";
  InputFile in(path);
  std::string line;
  ASSERT_TRUE(in.read_line(line));
  EXPECT_EQ(in.read_all(), "rest of\nthe file");
}

TEST(CsvReader, OverlongRowIsSplitOnlyUpToTheLimit) {
  const std::string path = test::scratch_path("wide-row.csv");
  {
    std::ofstream out(path);
    out << "a,b,c\n";
    for (int k = 0; k < 100000; ++k) out << k << ',';
    out << "end\n";
  }
  CsvReader reader(path);
  std::vector<CsvCell> cells;
  ASSERT_TRUE(reader.next_row(cells));
  reader.set_cell_limit(3);
  ASSERT_TRUE(reader.next_row(cells));
  EXPECT_EQ(cells.size(), 4u);
  EXPECT_EQ(reader.cell_count(), 100001u);
  EXPECT_EQ(cells[3].text, "3");
}

TEST(CsvReader, NumbersWithSignsAndRanges) {
  const std::string path = test::scratch_path("numbers.csv");
  std::ofstream(path) << "+0,+0.1,-2,1e400,inf,+-1,1e-310\n";
  CsvReader reader(path);
  std::vector<CsvCell> cells;
  ASSERT_TRUE(reader.next_row(cells));
  EXPECT_EQ(reader.number(cells[0]), 0.0);
  EXPECT_EQ(reader.number(cells[1]), 0.1);
  EXPECT_EQ(reader.number(cells[2]), -2.0);
  EXPECT_EQ(error_of([&] { reader.number(cells[3], "angle"); }),
            path + ":1:12: '1e400' is out of the range of double-precision numbers (angle)");
  EXPECT_EQ(error_of([&] { reader.number(cells[4], "angle"); }), path + ":1:18: 'inf' is not a finite angle");
  EXPECT_EQ(error_of([&] { reader.number(cells[5]); }), path + ":1:22: '+-1' is not a number");
  EXPECT_EQ(reader.number(cells[6]), 1e-310);
}

}  // namespace
}  // namespace roadbrdf
