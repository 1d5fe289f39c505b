// core/json_input.h: the one reader of user JSON. Depth limit, duplicate keys, number overflow,
// located errors (line, column, key path), integrality and range checks, and dumps of invalid UTF-8.
#include "roadbrdf/core/json_input.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "roadbrdf/core/error.h"

namespace roadbrdf {
namespace {

std::string error_of(const std::string& text) {
  try {
    parse_json_text(text, "f.json");
  } catch (const FileError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(JsonInput, NestingBeyondTheLimitIsAnErrorNotAStackOverflow) {
  const std::string deep = "{\"a\": " + std::string(200000, '[') + std::string(200000, ']') + "}";
  const std::string message = error_of(deep);
  EXPECT_NE(message.find("f.json:1:"), std::string::npos) << message;
  EXPECT_NE(message.find("a[0][0]"), std::string::npos) << message;
  EXPECT_NE(message.find("nested deeper than 64 levels"), std::string::npos) << message;
  // 64 levels are fine.
  EXPECT_NO_THROW(parse_json_text(std::string(64, '[') + std::string(64, ']'), "f.json"));
  EXPECT_THROW(parse_json_text(std::string(65, '[') + std::string(65, ']'), "f.json"), FileError);
}

TEST(JsonInput, DuplicateKeysAreErrorsNamingTheKeyPath) {
  const std::string message = error_of("{\"a\": {\"x\": 1,\n \"x\": 2}}");
  EXPECT_NE(message.find("f.json:2:"), std::string::npos) << message;
  EXPECT_NE(message.find("a.x: duplicate key"), std::string::npos) << message;
  // The same key in different objects is fine.
  EXPECT_NO_THROW(parse_json_text("[{\"x\": 1}, {\"x\": 2}]", "f.json"));
}

TEST(JsonInput, NumbersOutsideTheDoubleRangeAreLocated) {
  const std::string message = error_of("{\"p\": [1,\n 2, 1e400]}");
  EXPECT_NE(message.find("f.json:2:"), std::string::npos) << message;
  EXPECT_NE(message.find("p[2]"), std::string::npos) << message;
  EXPECT_NE(message.find("1e400"), std::string::npos) << message;
}

TEST(JsonInput, SyntaxErrorsHaveLineAndColumn) {
  const std::string message = error_of("{\n  \"a\": tru }");
  EXPECT_NE(message.find("f.json:2:"), std::string::npos) << message;
  EXPECT_NE(message.find("not valid JSON"), std::string::npos) << message;
}

TEST(JsonInput, IntegersKeepBothBoundsWhateverTheirJsonType) {
  // JSON parsers store 0 and 7 as unsigned, -1 as signed and 1.0 as a float: each must meet both bounds.
  const Json j = parse_json_text(R"({"zero": 0, "seven": 7, "minus": -1, "one": 1.0})", "i.json");
  const JsonNode root(j, "i.json");
  EXPECT_THROW(root.at("zero").integer(1, 20), FileError);
  EXPECT_EQ(root.at("zero").integer(0, 20), 0);
  EXPECT_THROW(root.at("seven").integer(8, 20), FileError);
  EXPECT_THROW(root.at("seven").integer(1, 6), FileError);
  EXPECT_EQ(root.at("seven").integer(7, 7), 7);
  EXPECT_THROW(root.at("minus").integer(0, 5), FileError);
  EXPECT_EQ(root.at("minus").integer(-1, 5), -1);
  EXPECT_THROW(root.at("one").integer(2, 5), FileError);
}

TEST(JsonInput, NodesNameTheKeyPathOfEveryTypeError) {
  const Json j = parse_json_text(R"({"fits": [{"model": 3, "n": 1.5, "big": 1e10, "ok": 2.0}]})", "f.json");
  const JsonNode root(j, "f.json");
  const JsonNode fit = root.at("fits")[0];
  try {
    fit.at("model").string();
    FAIL();
  } catch (const FileError& e) {
    EXPECT_STREQ(e.what(), "f.json: fits[0].model: must be a string, not number");
  }
  EXPECT_THROW(fit.at("n").integer(0, 10), FileError);      // 1.5 is not an integer
  EXPECT_THROW(fit.at("big").integer(0, 1000), FileError);  // out of range, no undefined cast
  EXPECT_EQ(fit.at("ok").integer(0, 10), 2);
  try {
    fit.at("missing");
    FAIL();
  } catch (const FileError& e) {
    EXPECT_STREQ(e.what(), "f.json: fits[0].missing: missing");
  }
}

TEST(JsonInput, DumpsReplaceInvalidUtf8) {
  Json j;
  j["path"] = std::string("bad\xff.csv");
  EXPECT_EQ(dump_json(j), "{\"path\":\"bad\xef\xbf\xbd.csv\"}");
}

// write_json streams in 64 kB blocks: the text must be that of dump_json, for documents smaller and
// much larger than a block, compact and indented, with invalid UTF-8 replaced the same way.
TEST(JsonInput, WriteJsonEqualsDumpJson) {
  Json big;
  big["path"] = std::string("bad\xff.csv");
  for (int k = 0; k < 20000; ++k) {
    big["values"].push_back(1.0 / (k + 3));
    big["nested"]["names"].push_back("n" + std::to_string(k));
  }
  nlohmann::ordered_json ordered;
  ordered["z"] = 1;
  ordered["a"] = big["values"];
  for (const int indent : {-1, 0, 1, 2}) {
    for (const Json& j : {Json{{"a", 1}}, big}) {
      std::ostringstream out;
      write_json(out, j, indent);
      EXPECT_EQ(out.str(), dump_json(j, indent)) << "indent " << indent;
    }
    std::ostringstream out;
    write_json(out, ordered, indent);
    EXPECT_EQ(out.str(), dump_json(ordered, indent)) << "indent " << indent;
  }
}

}  // namespace
}  // namespace roadbrdf
