#include "roadbrdf/core/json_input.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <memory>
#include <set>
#include <sstream>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/input_file.h"

namespace roadbrdf {

namespace {

// "[k]", built by appending (g++ 12 warns falsely, -Wrestrict, on "[" + to_string(k) + "]").
std::string index_suffix(std::size_t k) {
  std::string s(1, '[');
  s += std::to_string(k);
  s += ']';
  return s;
}

// A character iterator that records how far the parser has read, so that errors raised from the
// parser callback (depth, duplicate key) and nlohmann's number overflow get a line and column.
class TrackingIterator {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  TrackingIterator(const char* p, const char** furthest) : p_(p), furthest_(furthest) {}
  reference operator*() const { return *p_; }
  TrackingIterator& operator++() {
    ++p_;
    if (p_ > *furthest_) *furthest_ = p_;
    return *this;
  }
  TrackingIterator operator++(int) {
    TrackingIterator old = *this;
    ++*this;
    return old;
  }
  bool operator==(const TrackingIterator& o) const { return p_ == o.p_; }
  bool operator!=(const TrackingIterator& o) const { return p_ != o.p_; }

 private:
  const char* p_;
  const char** furthest_;
};

// Where the parser is: one frame per open object or array.
struct Frame {
  bool is_object = false;
  std::size_t index = 0;  // arrays: elements completed so far
  std::string key;        // objects: the current key
  std::set<std::string> keys;
};

std::string path_of(const std::vector<Frame>& frames) {
  std::string path;
  for (const auto& f : frames) {
    if (f.is_object) {
      if (f.key.empty() && f.keys.empty()) continue;
      if (!path.empty()) path += '.';
      path += f.key;
    } else {
      path += index_suffix(f.index);
    }
  }
  return path;
}

// nlohmann's message without its "[json.exception...] parse error at line L, column C: " prefix.
std::string parser_message(const std::string& what) {
  const auto column = what.find("column ");
  if (column != std::string::npos) {
    const auto colon = what.find(": ", column);
    if (colon != std::string::npos) return what.substr(colon + 2);
  }
  const auto bracket = what.find("] ");
  return bracket == std::string::npos ? what : what.substr(bracket + 2);
}

void line_column(const std::string& text, std::size_t offset, long& line, long& column) {
  offset = std::min(offset, text.size());
  line = 1;
  column = 1;
  for (std::size_t k = 0; k < offset; ++k) {
    if (text[k] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
}

}  // namespace

Json parse_json_text(const std::string& text, const std::string& file, int max_depth) {
  const char* begin = text.data();
  const char* end = begin + text.size();
  const char* furthest = begin;
  std::vector<Frame> frames;
  std::string error;  // set by the callback before it stops the parser

  const Json::parser_callback_t callback = [&](int depth, Json::parse_event_t event, Json& parsed) -> bool {
    using E = Json::parse_event_t;
    auto completed = [&] {
      if (!frames.empty() && !frames.back().is_object) ++frames.back().index;
    };
    switch (event) {
      case E::object_start:
      case E::array_start:
        if (depth >= max_depth) {
          error = "nested deeper than " + std::to_string(max_depth) + " levels";
          throw InputError(error);
        }
        frames.push_back(Frame{event == E::object_start, 0, {}, {}});
        break;
      case E::key: {
        Frame& f = frames.back();
        const std::string key = parsed.get<std::string>();
        f.key = key;
        if (!f.keys.insert(key).second) {
          error = "duplicate key";
          throw InputError(error);
        }
        break;
      }
      case E::object_end:
      case E::array_end:
        if (!frames.empty()) frames.pop_back();
        completed();
        break;
      case E::value:
        completed();
        break;
    }
    return true;
  };

  long line = 0, column = 0;
  try {
    return Json::parse(TrackingIterator(begin, &furthest), TrackingIterator(end, &furthest), callback);
  } catch (const Json::parse_error& e) {
    line_column(text, e.byte > 0 ? e.byte - 1 : 0, line, column);
    const std::string where = path_of(frames);
    throw FileError(
        file, line, column,
        "not valid JSON" + (where.empty() ? std::string() : " (at " + where + ")") + ": " + parser_message(e.what()));
  } catch (const Json::exception& e) {
    // Number overflow (1e400) and the like: located by how far the parser had read.
    line_column(text, static_cast<std::size_t>(furthest - begin), line, column);
    const std::string where = path_of(frames);
    throw FileError(file, line, column,
                    (where.empty() ? std::string("(top level)") : where) + ": " + parser_message(e.what()));
  } catch (const InputError&) {
    line_column(text, static_cast<std::size_t>(furthest - begin), line, column);
    const std::string where = path_of(frames);
    throw FileError(file, line, column, (where.empty() ? std::string("(top level)") : where) + ": " + error);
  }
}

Json parse_json(std::istream& in, const std::string& file, int max_depth) {
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw FileError(file, 0, 0, "read error");
  return parse_json_text(text.str(), file, max_depth);
}

Json parse_json_file(const std::string& path, int max_depth) {
  InputLimits limits;
  limits.what = "a JSON file";
  limits.max_bytes = kJsonFileMaxBytes;
  return parse_json_text(read_text_file(path, limits), input_display_name(path), max_depth);
}

std::string dump_json(const Json& j, int indent) { return j.dump(indent, ' ', false, Json::error_handler_t::replace); }

std::string dump_json(const nlohmann::ordered_json& j, int indent) {
  return j.dump(indent, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

namespace {

// nlohmann's serializer writes a character or a short run at a time; this adapter gathers them into
// 64 KiB blocks for the stream, so that a large document is never held whole as a string (a 1 MB
// fit file would otherwise cost its string's repeated growth and the page faults of 2-3 MB), and
// the stream is not called (with its sentry) for every character, as nlohmann's own adapter does.
class BlockStreamAdapter : public nlohmann::detail::output_adapter_protocol<char> {
 public:
  explicit BlockStreamAdapter(std::ostream& out) : out_(out) { block_.reserve(kBlock); }
  BlockStreamAdapter(const BlockStreamAdapter&) = delete;
  BlockStreamAdapter& operator=(const BlockStreamAdapter&) = delete;
  ~BlockStreamAdapter() override = default;

  void write_character(char c) override {
    block_.push_back(c);
    if (block_.size() >= kBlock) flush();
  }
  void write_characters(const char* s, std::size_t length) override {
    block_.append(s, length);
    if (block_.size() >= kBlock) flush();
  }
  void flush() {
    out_.write(block_.data(), static_cast<std::streamsize>(block_.size()));
    block_.clear();
  }

 private:
  static constexpr std::size_t kBlock = std::size_t{1} << 16;
  std::ostream& out_;
  std::string block_;
};

template <typename Document>
void write_document(std::ostream& out, const Document& j, int indent) {
  auto adapter = std::make_shared<BlockStreamAdapter>(out);
  nlohmann::detail::serializer<Document> serializer(adapter, ' ', Document::error_handler_t::replace);
  serializer.dump(j, indent >= 0, false, static_cast<unsigned int>(std::max(indent, 0)));
  adapter->flush();
}

}  // namespace

void write_json(std::ostream& out, const Json& j, int indent) { write_document(out, j, indent); }

void write_json(std::ostream& out, const nlohmann::ordered_json& j, int indent) { write_document(out, j, indent); }

std::vector<double> read_parameter_table(const JsonNode& parameters, const ModelDescription& description,
                                         std::size_t rows, const std::vector<double>& wavelengths) {
  const std::size_t n = description.parameters.size();
  std::vector<double> table(rows * n);
  for (std::size_t q = 0; q < n; ++q) {
    const ParameterInfo& info = description.parameters[q];
    const auto [lower, upper] = description.physical_range(q);
    const JsonNode values = parameters.at(info.name);
    if (values.size() != rows) {
      values.fail("has " + std::to_string(values.size()) + " values for " + std::to_string(rows) + " wavelength" +
                  (rows == 1 ? "" : "s"));
    }
    for (std::size_t w = 0; w < rows; ++w) {
      const JsonNode v = values[w];
      const double x = v.number();
      if (x < lower || x > upper) {
        std::ostringstream msg;
        msg << "parameter '" << info.name << "' of model '" << description.name << "' = " << x;
        if (w < wavelengths.size()) msg << " at " << wavelengths[w] << " nm";
        msg << " is outside its bounds [" << lower << ", " << upper << "]";
        v.fail(msg.str());
      }
      table[w * n + q] = x;
    }
  }
  return table;
}

// ---------------------------------------------------------------------------------------------

JsonNode::JsonNode(const Json& value, std::string file, std::string path)
    : value_(&value), file_(std::move(file)), path_(std::move(path)) {}

std::string JsonNode::where() const { return path_.empty() ? std::string("(top level)") : path_; }

void JsonNode::fail(const std::string& what) const { throw FileError(file_, 0, 0, where() + ": " + what); }

std::string JsonNode::type_name() const { return value_->type_name(); }

JsonNode JsonNode::child(const Json& value, const std::string& suffix) const {
  return JsonNode(value, file_, path_ + suffix);
}

bool JsonNode::has(const std::string& key) const { return value_->is_object() && value_->contains(key); }

JsonNode JsonNode::at(const std::string& key) const {
  if (!value_->is_object()) fail("must be an object, not " + type_name());
  const auto it = value_->find(key);
  const std::string suffix = path_.empty() ? key : "." + key;
  if (it == value_->end()) throw FileError(file_, 0, 0, path_ + suffix + ": missing");
  return child(*it, suffix);
}

std::optional<JsonNode> JsonNode::find(const std::string& key) const {
  if (!value_->is_object()) fail("must be an object, not " + type_name());
  const auto it = value_->find(key);
  if (it == value_->end()) return std::nullopt;
  return child(*it, path_.empty() ? key : "." + key);
}

std::vector<std::pair<std::string, JsonNode>> JsonNode::members() const {
  if (!value_->is_object()) fail("must be an object, not " + type_name());
  std::vector<std::pair<std::string, JsonNode>> out;
  for (auto it = value_->begin(); it != value_->end(); ++it) {
    out.emplace_back(it.key(), child(it.value(), path_.empty() ? it.key() : "." + it.key()));
  }
  return out;
}

void JsonNode::check_keys(const std::vector<std::string>& allowed) const {
  for (const auto& [key, node] : members()) {
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
    node.fail("unknown key (allowed: " + list + ")");
  }
}

std::size_t JsonNode::size() const {
  if (!value_->is_array()) fail("must be an array, not " + type_name());
  return value_->size();
}

JsonNode JsonNode::operator[](std::size_t index) const {
  if (index >= size()) fail("has no element " + std::to_string(index));
  return child((*value_)[index], index_suffix(index));
}

std::vector<JsonNode> JsonNode::elements() const {
  std::vector<JsonNode> out;
  const std::size_t n = size();
  out.reserve(n);
  for (std::size_t k = 0; k < n; ++k) out.push_back(child((*value_)[k], index_suffix(k)));
  return out;
}

std::string JsonNode::string() const {
  if (!value_->is_string()) fail("must be a string, not " + type_name());
  return value_->get<std::string>();
}

bool JsonNode::boolean() const {
  if (!value_->is_boolean()) fail("must be true or false, not " + type_name());
  return value_->get<bool>();
}

double JsonNode::number() const {
  if (!value_->is_number()) fail("must be a number, not " + type_name());
  const double x = value_->get<double>();
  if (!std::isfinite(x)) fail("must be finite");
  return x;
}

long long JsonNode::integer(long long lo, long long hi) const {
  if (!value_->is_number()) fail("must be an integer, not " + type_name());
  const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (value_->is_number_unsigned()) {
    const auto u = value_->get<std::uint64_t>();
    // Both bounds: an unsigned value may still lie below a positive lower bound (0 with lo = 1).
    if (hi < 0 || u > static_cast<std::uint64_t>(hi) || (lo > 0 && u < static_cast<std::uint64_t>(lo)))
      fail("must be an integer in " + range + ", got " + value_->dump());
    return static_cast<long long>(u);
  }
  if (value_->is_number_integer()) {
    const auto i = value_->get<std::int64_t>();
    if (i < lo || i > hi) fail("must be an integer in " + range + ", got " + value_->dump());
    return i;
  }
  const double x = value_->get<double>();
  // Compare in double before converting: a cast of an out-of-range double is undefined.
  // (2^63 bounds the conversion: double(hi) may round up to it.)
  if (!std::isfinite(x) || x != std::floor(x) || x < static_cast<double>(lo) || x > static_cast<double>(hi) ||
      x >= 0x1p63 || x < -0x1p63) {
    fail("must be an integer in " + range + ", got " + value_->dump());
  }
  return static_cast<long long>(x);
}

std::vector<double> JsonNode::numbers() const {
  std::vector<double> out;
  out.reserve(size());
  for (const auto& e : elements()) out.push_back(e.number());
  return out;
}

std::vector<std::string> JsonNode::strings() const {
  std::vector<std::string> out;
  out.reserve(size());
  for (const auto& e : elements()) out.push_back(e.string());
  return out;
}

std::vector<long long> JsonNode::integers(long long lo, long long hi) const {
  std::vector<long long> out;
  out.reserve(size());
  for (const auto& e : elements()) out.push_back(e.integer(lo, hi));
  return out;
}

std::map<std::string, std::string> JsonNode::string_map() const {
  std::map<std::string, std::string> out;
  for (const auto& [key, node] : members()) out[key] = node.string();
  return out;
}

std::map<std::string, double> JsonNode::number_map() const {
  std::map<std::string, double> out;
  for (const auto& [key, node] : members()) out[key] = node.number();
  return out;
}

std::string JsonNode::string_or(const std::string& key, const std::string& fallback) const {
  const auto n = find(key);
  return n ? n->string() : fallback;
}

double JsonNode::number_or(const std::string& key, double fallback) const {
  const auto n = find(key);
  return n ? n->number() : fallback;
}

bool JsonNode::boolean_or(const std::string& key, bool fallback) const {
  const auto n = find(key);
  return n ? n->boolean() : fallback;
}

}  // namespace roadbrdf
