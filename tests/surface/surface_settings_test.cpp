// The render settings' checks made once, where every render passes (validate_sampling,
// surface/scheduler.h): max_samples < 2 is refused with the request field's name, with a fixed path
// count as with an adaptive one, and a request (render_settings) is refused by the same check.
#include <gtest/gtest.h>

#include <string>

#include "roadbrdf/core/error.h"
#include "roadbrdf/surface/render.h"
#include "roadbrdf/surface/render_request.h"
#include "roadbrdf/surface/scheduler.h"

namespace rs = roadbrdf::surface;

namespace {

template <class F>
std::string refused_field(F&& call, std::string* detail) {
  try {
    call();
  } catch (const roadbrdf::FieldError& e) {
    *detail = e.detail();
    return e.field();
  }
  return "";
}

TEST(RenderSettingsChecks, MaxSamplesBelowTwoIsRefusedInBothModes) {
  for (const double target : {0.0, 0.01}) {
    rs::RenderSettings s;
    s.samples = 64;
    s.target_relative_error = target;
    s.max_samples = 1;
    std::string detail;
    EXPECT_EQ(refused_field([&] { rs::validate_sampling(s); }, &detail), "max_samples") << target;
    EXPECT_EQ(detail, "1 is below 2");
    s.max_samples = 2;
    EXPECT_NO_THROW(rs::validate_sampling(s)) << target;
  }
}

TEST(RenderSettingsChecks, ARequestIsCheckedByTheSameRule) {
  rs::RenderRequest r;
  r.samples = 64;
  r.max_samples = 0;
  std::string detail;
  EXPECT_EQ(refused_field([&] { rs::render_settings(r); }, &detail), "max_samples");
  EXPECT_EQ(detail, "0 is below 2");
  r.max_samples = 2;
  EXPECT_EQ(rs::render_settings(r).max_samples, 2);
}

}  // namespace
