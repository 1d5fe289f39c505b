#include "roadbrdf/photometry/rtable_io.h"

#include <fmt/core.h>

#include <cctype>
#include <charconv>
#include <fstream>
#include <ostream>
#include <sstream>
#include <vector>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/input_file.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/text.h"

namespace roadbrdf::photometry {

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Shortest text that reads back to the same double.
std::string number_text(double x) { return fmt::format("{}", x); }
std::string cell_text(double scaled) { return std::isnan(scaled) ? std::string("0") : number_text(scaled); }

struct Token {
  std::string text;
  long line = 0;
  long column = 0;
};

// Whitespace-separated tokens with their positions. "\r\n", "\n" and a lone "\r" end a line.
std::vector<Token> tokenize(const std::string& content, long first_line = 1) {
  std::vector<Token> tokens;
  long line = first_line, column = 1;
  std::size_t k = 0;
  while (k < content.size()) {
    const char c = content[k];
    if (c == '\n' || c == '\r') {
      if (c == '\r' && k + 1 < content.size() && content[k + 1] == '\n') ++k;
      ++line;
      column = 1;
      ++k;
      continue;
    }
    if (c == ' ' || c == '\t' || c == '\f' || c == '\v') {
      ++column;
      ++k;
      continue;
    }
    Token t;
    t.line = line;
    t.column = column;
    while (k < content.size() && !std::isspace(static_cast<unsigned char>(content[k]))) {
      t.text.push_back(content[k]);
      ++k;
      ++column;
    }
    tokens.push_back(std::move(t));
  }
  return tokens;
}

// An r-table file holds a few hundred numbers.
std::string read_all(const std::string& path) {
  InputLimits limits;
  limits.what = "an r-table file";
  limits.max_bytes = std::uintmax_t{64} << 20;
  return read_text_file(path, limits);
}

class TokenStream {
 public:
  TokenStream(std::string path, std::vector<Token> tokens) : path_(std::move(path)), tokens_(std::move(tokens)) {}
  bool done() const { return next_ >= tokens_.size(); }
  const Token& peek() const { return tokens_[next_]; }
  double number(const std::string& what) {
    if (done()) throw FileError(path_, last_line(), 0, "unexpected end of file: expected " + what);
    const Token& t = tokens_[next_++];
    double v = 0.0;
    if (!parse_finite_double(t.text, v)) {
      throw FileError(path_, t.line, t.column, "'" + t.text + "' is not a " + what);
    }
    last_ = t;
    return v;
  }
  long count(const std::string& what) {
    const double v = number(what);
    if (v != std::floor(v) || v < 1 || v > 100000) fail_last("'" + last_.text + "' is not a valid " + what);
    return static_cast<long>(v);
  }
  [[noreturn]] void fail_last(const std::string& message) const {
    throw FileError(path_, last_.line, last_.column, message);
  }
  [[noreturn]] void fail_at_next(const std::string& message) const {
    if (done()) throw FileError(path_, last_line(), 0, message);
    throw FileError(path_, peek().line, peek().column, message);
  }
  const Token& last() const { return last_; }

 private:
  long last_line() const { return tokens_.empty() ? 0 : tokens_.back().line; }
  std::string path_;
  std::vector<Token> tokens_;
  std::size_t next_ = 0;
  Token last_;
};

bool matches_tan(double t_file, std::size_t row) {
  const double g_file = rad_to_deg(std::atan(t_file));
  return std::abs(g_file - gamma_deg(row)) <= 0.006;
}
bool matches_gamma_deg(double g_file, std::size_t row) { return std::abs(g_file - gamma_deg(row)) <= 0.006; }
bool matches_beta(double b_file, std::size_t column) { return std::abs(b_file - standard_beta_deg()[column]) <= 0.001; }

// File value -> stored R (1e4 r); 0 = missing.
double stored_value(double file_value, double scale) {
  if (file_value == 0.0) return std::nan("");
  return scale == kRScale ? file_value : file_value * (kRScale / scale);
}

void check_value(TokenStream& s, double v) {
  if (v < 0.0) s.fail_last("negative reduced luminance coefficient '" + s.last().text + "'");
}

// ---- CSV --------------------------------------------------------------------------------------

// The header row: tan_gamma and the 20 standard beta values [deg].
void check_csv_header(CsvReader& reader, const std::vector<CsvCell>& cells) {
  if (cells.size() != kColumns + 1) {
    reader.fail(cells.size() > kColumns + 1 ? cells[kColumns + 1].column : cells.back().column,
                "header: expected tan_gamma and 20 beta values, got " + std::to_string(cells.size()) + " cells");
  }
  for (std::size_t j = 0; j < kColumns; ++j) {
    const double b = reader.number(cells[j + 1], "beta [deg]");
    if (!matches_beta(b, j)) {
      reader.fail(cells[j + 1].column, "beta = " + std::string(cells[j + 1].text) + " deg; the standard grid has " +
                                           number_text(standard_beta_deg()[j]) + " here");
    }
  }
}

// One row of values (row 0-based), with its tan(gamma) cell first when the table has that column.
void read_csv_row(CsvReader& reader, const std::vector<CsvCell>& cells, std::size_t row, bool with_tan_column,
                  double scale, RTable& table) {
  if (row >= kRows) reader.fail(cells.front().column, "more than 29 rows of values");
  const std::size_t expected = with_tan_column ? kColumns + 1 : kColumns;
  if (cells.size() != expected) {
    // Located at the first extra cell, or after the last one when cells are missing.
    const long column = cells.size() > expected ? cells[expected].column
                                                : cells.back().column + static_cast<long>(cells.back().text.size());
    reader.fail(column, "expected " + std::to_string(expected) + " cells, got " + std::to_string(cells.size()));
  }
  std::size_t first = 0;
  if (with_tan_column) {
    const double t = reader.number(cells[0], "tan(gamma)");
    if (!matches_tan(t, row)) {
      reader.fail(cells[0].column, "tan(gamma) = " + std::string(cells[0].text) + "; row " + std::to_string(row + 1) +
                                       " of the standard grid is " + number_text(standard_tan_gamma()[row]));
    }
    first = 1;
  }
  for (std::size_t j = 0; j < kColumns; ++j) {
    const CsvCell& c = cells[first + j];
    if (c.text.empty() || lower(std::string(c.text)) == "nan") continue;  // missing
    const double v = reader.number(c, "reduced luminance coefficient");
    if (v < 0.0) reader.fail(c.column, "negative reduced luminance coefficient");
    table.at(row, j) = stored_value(v, scale);
  }
}

// The comment lines' metadata: "alpha_deg = A" (the observation angle) and "name: N".
void read_csv_comments(const std::string& path, CsvReader& reader, RTable& table) {
  for (std::size_t k = 0; k < reader.comments().size(); ++k) {
    const std::string c = reader.comments()[k];
    const auto key = c.find("alpha_deg");
    const auto eq = c.find('=');
    if (key != std::string::npos && eq != std::string::npos && eq > key) {
      // The whole value must be the observation angle in degrees, 0 < alpha < 90 ("1abc" is no angle).
      const auto start = c.find_first_not_of(kBlankCharacters, eq + 1);
      const auto end = c.find_last_not_of(kBlankCharacters);
      const std::string v = start == std::string::npos ? std::string() : c.substr(start, end - start + 1);
      double a = 0.0;
      if (!parse_finite_double(v, a) || !(a > 0.0 && a < 90.0)) {
        // +2: the comment text starts after '#' in column 1.
        throw FileError(path, reader.comment_lines()[k], static_cast<long>(start == std::string::npos ? eq : start) + 2,
                        "alpha_deg = '" + v + "' is not an observation angle in (0, 90) deg");
      }
      table.alpha_deg = a;
    }
    const auto name = c.find("name:");
    if (name != std::string::npos) {
      const std::string n = trimmed_copy(std::string_view(c).substr(name + 5));
      if (!n.empty()) table.name = n;
    }
  }
}

RTable read_csv(const std::string& path, double scale) {
  CsvReader reader(path);
  std::vector<CsvCell> cells;
  RTable table;
  table.name = path;
  bool header_seen = false;
  bool with_tan_column = false;
  std::size_t row = 0;
  while (reader.next_row(cells)) {
    if (row == 0 && !header_seen) {
      // A header row's first cell is not a number.
      if (!is_number_text(cells[0].text)) {
        header_seen = true;
        with_tan_column = true;
        check_csv_header(reader, cells);
        continue;
      }
      with_tan_column = cells.size() == kColumns + 1;
    }
    read_csv_row(reader, cells, row, with_tan_column, scale, table);
    ++row;
  }
  if (row != kRows)
    throw FileError(path, reader.line_number(), 0, "expected 29 rows of values, got " + std::to_string(row));
  read_csv_comments(path, reader, table);
  return table;
}

void write_csv(std::ostream& out, const RTable& table) {
  out << "# roadbrdf r-table. Values are R = 1e4 * r, r = q cos^3(gamma) the reduced luminance coefficient "
         "[sr^-1]; 0 = cell not defined (missing)\n";
  out << "# name: " << table.name << "\n";
  out << "# alpha_deg = " << number_text(table.alpha_deg) << "\n";
  out << "# rows: tan(gamma); columns: beta [deg] (0 = forward side)\n";
  out << "tan_gamma";
  for (double b : standard_beta_deg()) out << ',' << number_text(b);
  out << '\n';
  for (std::size_t i = 0; i < kRows; ++i) {
    out << number_text(standard_tan_gamma()[i]);
    for (std::size_t j = 0; j < kColumns; ++j) out << ',' << cell_text(table.at(i, j));
    out << '\n';
  }
}

// ---- RTB --------------------------------------------------------------------------------------

RTableFile read_rtb(const std::string& path, double scale) {
  const std::string content = read_all(path);
  // Lines 1 and 2 (the name may contain spaces).
  std::size_t pos = 0;
  auto next_line = [&](std::string& line) {
    if (pos >= content.size()) return false;
    std::size_t end = content.find_first_of("\r\n", pos);
    if (end == std::string::npos) end = content.size();
    line = content.substr(pos, end - pos);
    pos = end;
    if (pos < content.size() && content[pos] == '\r') ++pos;
    if (pos < content.size() && content[pos] == '\n') ++pos;
    return true;
  };
  std::string magic, name;
  if (!next_line(magic)) throw FileError(path, 1, 0, "empty file");
  auto trim = [](const std::string& s) { return trimmed_copy(s); };
  if (!magic.empty() && static_cast<unsigned char>(magic[0]) == 0xEF && magic.size() >= 3) magic.erase(0, 3);  // BOM
  if (trim(magic) != "RTable.v1") throw FileError(path, 1, 1, "not an RTB file: the first line is not 'RTable.v1'");
  if (!next_line(name)) throw FileError(path, 2, 0, "missing the table name (line 2)");
  TokenStream s(path, tokenize(content.substr(pos), 3));
  RTableFile file;
  file.format = RTableFormat::rtb;
  file.table.name = trim(name);
  const long n_eps = s.count("number of tan(gamma) values");
  if (n_eps != static_cast<long>(kRows)) s.fail_last("expected 29 tan(gamma) values, got " + s.last().text);
  for (std::size_t i = 0; i < kRows; ++i) {
    const double t = s.number("tan(gamma)");
    if (!matches_tan(t, i)) {
      s.fail_last("tan(gamma) = " + s.last().text + "; the standard grid has " + number_text(standard_tan_gamma()[i]));
    }
  }
  const long n_beta = s.count("number of beta values");
  if (n_beta != static_cast<long>(kColumns)) s.fail_last("expected 20 beta values, got " + s.last().text);
  for (std::size_t j = 0; j < kColumns; ++j) {
    const double b = s.number("beta [deg]");
    if (!matches_beta(b, j)) {
      s.fail_last("beta = " + s.last().text + " deg; the standard grid has " + number_text(standard_beta_deg()[j]));
    }
  }
  file.declared_q0 = s.number("q0");
  for (std::size_t j = 0; j < kColumns; ++j) {
    for (std::size_t i = 0; i < kRows; ++i) {  // tan(gamma) fastest
      const double v = s.number("reduced luminance coefficient");
      check_value(s, v);
      file.table.at(i, j) = stored_value(v, scale);
    }
  }
  if (!s.done()) s.fail_at_next("unexpected content after the 580 table values");
  return file;
}

void write_rtb(std::ostream& out, const RTable& table) {
  // DIALux reads one item per line; CRLF as written by Windows tools is not required.
  out << "RTable.v1\n";
  std::string name = table.name;
  for (char& c : name) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  out << (name.empty() ? std::string("roadbrdf") : name) << '\n';
  out << kRows << '\n';
  for (double t : standard_tan_gamma()) out << number_text(t) << '\n';
  out << kColumns << '\n';
  for (double b : standard_beta_deg()) out << number_text(b) << '\n';
  double q = 0.0;
  try {
    q = q0(table);
  } catch (const InputError&) {
    q = 0.0;
  }
  out << number_text(q) << '\n';
  for (std::size_t j = 0; j < kColumns; ++j) {
    for (std::size_t i = 0; i < kRows; ++i) out << cell_text(table.at(i, j)) << '\n';
  }
}

// ---- Radiance data file ----------------------------------------------------------------------

std::vector<double> read_axis(TokenStream& s, const std::string& what) {
  const double begin = s.number(what + " axis start");
  const double end = s.number(what + " axis end");
  const long n = s.count("number of " + what + " values");
  std::vector<double> axis(static_cast<std::size_t>(n));
  if (begin == 0.0 && end == 0.0) {
    for (auto& x : axis) x = s.number(what + " value");
  } else {
    for (long k = 0; k < n; ++k) {
      axis[static_cast<std::size_t>(k)] = n == 1 ? begin : begin + (end - begin) * static_cast<double>(k) / (n - 1);
    }
  }
  return axis;
}

RTable read_radiance(const std::string& path, double alpha_deg, double scale) {
  TokenStream s(path, tokenize(read_all(path)));
  const long dims = s.count("number of dimensions");
  if (dims != 3) s.fail_last("expected 3 dimensions (alpha, gamma, beta), got " + s.last().text);
  const std::vector<double> alpha = read_axis(s, "alpha");
  const Token alpha_token = s.last();
  const std::vector<double> gamma = read_axis(s, "gamma");
  const Token gamma_token = s.last();
  const std::vector<double> beta = read_axis(s, "beta");
  const Token beta_token = s.last();
  if (gamma.size() != kRows) {
    throw FileError(path, gamma_token.line, 0, "expected 29 gamma values, got " + std::to_string(gamma.size()));
  }
  for (std::size_t i = 0; i < kRows; ++i) {
    if (!matches_gamma_deg(gamma[i], i)) {
      throw FileError(path, gamma_token.line, 0,
                      "gamma = " + number_text(gamma[i]) + " deg; the standard grid has atan(" +
                          number_text(standard_tan_gamma()[i]) + ") = " + fmt::format("{:.4f}", gamma_deg(i)) + " deg");
    }
  }
  if (beta.size() != kColumns) {
    throw FileError(path, beta_token.line, 0, "expected 20 beta values, got " + std::to_string(beta.size()));
  }
  for (std::size_t j = 0; j < kColumns; ++j) {
    if (!matches_beta(beta[j], j)) {
      throw FileError(
          path, beta_token.line, 0,
          "beta = " + number_text(beta[j]) + " deg; the standard grid has " + number_text(standard_beta_deg()[j]));
    }
  }
  std::size_t slice = alpha.size();
  for (std::size_t a = 0; a < alpha.size(); ++a) {
    if (std::abs(alpha[a] - alpha_deg) <= 0.01) slice = a;
  }
  if (slice == alpha.size()) {
    throw FileError(path, alpha_token.line, 0,
                    "the file has no alpha = " + number_text(alpha_deg) + " deg slice (use `alpha` to select one)");
  }
  RTable table;
  table.name = path;
  table.alpha_deg = alpha[slice];
  for (std::size_t a = 0; a < alpha.size(); ++a) {
    for (std::size_t i = 0; i < kRows; ++i) {
      for (std::size_t j = 0; j < kColumns; ++j) {
        const double v = s.number("reduced luminance coefficient");
        check_value(s, v);
        if (a == slice) table.at(i, j) = stored_value(v, scale);
      }
    }
  }
  if (!s.done()) s.fail_at_next("unexpected content after the table values");
  return table;
}

void write_radiance(std::ostream& out, const RTable& table) {
  if (!(table.alpha_deg > 0.0 && table.alpha_deg < 90.0)) {
    throw InputError("Radiance r-table: alpha = " + number_text(table.alpha_deg) + " deg must be in (0, 90)");
  }
  out << "3\n0 0 3\n0 " << number_text(table.alpha_deg) << " 90\n\n";
  out << "0 0 " << kRows << '\n';
  for (std::size_t i = 0; i < kRows; ++i) out << number_text(gamma_deg(i)) << '\n';
  out << "\n0 0 " << kColumns << '\n';
  for (double b : standard_beta_deg()) out << number_text(b) << '\n';
  for (int a = 0; a < 3; ++a) {
    out << '\n';
    for (std::size_t i = 0; i < kRows; ++i) {
      for (std::size_t j = 0; j < kColumns; ++j) {
        if (j > 0) out << ' ';
        out << (a == 1 ? cell_text(table.at(i, j)) : std::string("0"));
      }
      out << '\n';
    }
  }
}

}  // namespace

RTableFormat rtable_format_from_name(const std::string& name, const std::string& field) {
  const std::string l = lower(name);
  return l == "dat" ? RTableFormat::radiance : parse_name<RTableFormat>(l, field);
}

std::optional<RTableFormat> rtable_format_from_path(const std::string& path) {
  const auto dot = path.find_last_of('.');
  const auto slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return std::nullopt;
  const std::string ext = lower(path.substr(dot));
  if (ext == ".csv") return RTableFormat::csv;
  if (ext == ".rtb") return RTableFormat::rtb;
  if (ext == ".dat" || ext == ".cal") return RTableFormat::radiance;
  return std::nullopt;
}

RTableFile read_rtable(const std::string& path, std::optional<RTableFormat> format, double alpha_deg, double scale) {
  if (!(scale > 0.0) || !std::isfinite(scale)) throw InputError("r-table scale must be a positive number");
  if (!format) format = rtable_format_from_path(path);
  if (!format) {
    throw InputError("cannot tell the r-table format of '" + path +
                     "' from its extension (.csv, .rtb, .dat); give the format explicitly");
  }
  RTableFile file;
  file.format = *format;
  switch (*format) {
    case RTableFormat::csv:
      file.table = read_csv(path, scale);
      break;
    case RTableFormat::rtb:
      file = read_rtb(path, scale);
      break;
    case RTableFormat::radiance:
      file.table = read_radiance(path, alpha_deg, scale);
      break;
  }
  if (file.table.defined_count() == 0) throw FileError(path, 0, 0, "the r-table has no defined (non-zero) cell");
  return file;
}

namespace {

// A table is written only if every reader reads it back: defined cells finite and >= 0 (below
// 1e15, so that no reader's unit scaling overflows), at least one defined cell, a one-line name and
// an observation angle in (0, 90) deg.
void check_writable(const RTable& table) {
  if (table.scaled.size() != kRows * kColumns) throw InputError("r-table: expected 29 x 20 cells");
  for (std::size_t i = 0; i < kRows; ++i) {
    for (std::size_t j = 0; j < kColumns; ++j) {
      const double v = table.at(i, j);
      if (std::isnan(v)) continue;
      if (!(v >= 0.0 && v < 1e15)) {
        throw InputError(
            fmt::format("r-table cell (tan gamma {}, beta {} deg) = {} cannot be written: R = 1e4 r "
                        "must be finite, >= 0 and < 1e15",
                        standard_tan_gamma()[i], standard_beta_deg()[j], v));
      }
    }
  }
  if (table.defined_count() == 0) throw InputError("r-table has no defined cell: nothing to write");
  if (table.name.find_first_of("\r\n") != std::string::npos) throw InputError("r-table name must be one line");
  if (!(table.alpha_deg > 0.0 && table.alpha_deg < 90.0)) {
    throw InputError(fmt::format("r-table observation angle alpha = {} deg must be in (0, 90)", table.alpha_deg));
  }
}

}  // namespace

void write_rtable(std::ostream& out, const RTable& table, RTableFormat format) {
  check_writable(table);
  switch (format) {
    case RTableFormat::csv:
      write_csv(out, table);
      return;
    case RTableFormat::rtb:
      write_rtb(out, table);
      return;
    case RTableFormat::radiance:
      write_radiance(out, table);
      return;
  }
}

void write_rtable_file(const std::string& path, const RTable& table, RTableFormat format) {
  check_writable(table);  // before the output file is touched
  AtomicFile file(path);
  write_rtable(file.stream(), table, format);
  file.commit();
}

}  // namespace roadbrdf::photometry
