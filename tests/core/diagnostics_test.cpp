// Notes and warnings (core/diagnostics.h): structured diagnostics and the front end's sink for readers
// called without one of their own.
#include "roadbrdf/core/diagnostics.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace roadbrdf {
namespace {

TEST(Diagnostics, KeepKindAndMessageAndWriteThemAsJson) {
  Diagnostics d;
  d.note("single_band", "the fit has a single band");
  d.warn("extrapolated", "mostly extrapolated");
  EXPECT_TRUE(d.has_warning("extrapolated"));
  EXPECT_FALSE(d.has_warning("single_band"));
  const nlohmann::json j = d.to_json();
  EXPECT_EQ(j["notes"][0]["kind"], "single_band");
  EXPECT_EQ(j["warnings"][0]["message"], "mostly extrapolated");
  Diagnostics collected;
  const DiagnosticSink sink = collect_into(collected);
  sink(Severity::warning, {"w", "a warning"});
  sink(Severity::note, {"n", "a note"});
  ASSERT_EQ(collected.warnings.size(), 1u);
  EXPECT_EQ(collected.notes.front().kind, "n");
}

TEST(Diagnostics, WarningsWithoutASinkAreKeptThenRoutedToTheFrontEnd) {
  set_front_end_warning_sink(nullptr);
  (void)take_unrouted_warnings();
  route_warning("first");
  route_warning("second");
  EXPECT_EQ(take_unrouted_warnings(), (std::vector<std::string>{"first", "second"}));
  EXPECT_TRUE(take_unrouted_warnings().empty());
  std::vector<std::string> shown;
  set_front_end_warning_sink([&shown](const std::string& m) { shown.push_back(m); });
  route_warning("third");
  set_front_end_warning_sink(nullptr);
  EXPECT_EQ(shown, (std::vector<std::string>{"third"}));
  EXPECT_TRUE(take_unrouted_warnings().empty());
}

}  // namespace
}  // namespace roadbrdf
