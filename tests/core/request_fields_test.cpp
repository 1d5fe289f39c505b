// The request contract's table (core/request_fields.h): lookup, file roles and the check of
// distinct files made from them.
#include "roadbrdf/core/request_fields.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "roadbrdf/core/error.h"
#include "support/scratch.h"

namespace roadbrdf {
namespace {

struct ToyRequest {
  std::string input;
  std::string output;
  std::vector<std::string> extra;
  double height_m = 10.0;
  Source source;
  static RequestFields<ToyRequest> fields() {
    static const RequestField<ToyRequest> table[] = {
        {"input", "INPUT", "", "What is read", &ToyRequest::input, FileRole::input, true},
        {"output", "-o,--output", "", "What is written", &ToyRequest::output, FileRole::output},
        {"extra", "--extra", "", "More inputs", &ToyRequest::extra, FileRole::input},
        {"height_m", "--height", "m", "Mounting height", &ToyRequest::height_m},
        {"source", "--source,--src", "", "A file or its content", &ToyRequest::source, FileRole::input},
    };
    return table;
  }
};

TEST(RequestFields, FindsFieldsByNameAndByTheirFirstPart) {
  ASSERT_NE(find_field(ToyRequest::fields(), "height_m"), nullptr);
  EXPECT_EQ(find_field(ToyRequest::fields(), "height_m")->long_flag(), "--height");
  EXPECT_EQ(find_field(ToyRequest::fields(), "output")->long_flag(), "--output");
  EXPECT_EQ(find_field(ToyRequest::fields(), "source")->long_flag(), "--source");
  EXPECT_EQ(find_field(ToyRequest::fields(), "input")->long_flag(), "INPUT");
  EXPECT_EQ(find_field(ToyRequest::fields(), "extra.first")->name, "extra");
  EXPECT_EQ(find_field(ToyRequest::fields(), "height"), nullptr);
  EXPECT_TRUE(find_field(ToyRequest::fields(), "input")->positional());
  EXPECT_FALSE(find_field(ToyRequest::fields(), "output")->positional());
}

TEST(RequestFields, FileRowsBecomeInputsAndOutputsNamedByTheirField) {
  ToyRequest request;
  request.input = "a.csv";
  request.output = "b.csv";
  request.extra = {"c.csv", "d.csv"};
  std::vector<FileArgument> inputs, outputs;
  file_arguments(request, ToyRequest::fields(), inputs, outputs);
  ASSERT_EQ(inputs.size(), 3u);
  ASSERT_EQ(outputs.size(), 1u);
  EXPECT_EQ(inputs[0].role, "`input`");
  EXPECT_EQ(inputs[2].path, "d.csv");
  EXPECT_EQ(outputs[0].path, "b.csv");
}

TEST(RequestFields, ASourceIsAFileOnlyWhenNotGivenAsAValue) {
  ToyRequest request;
  request.source = Source{"s.json", {}};
  std::vector<FileArgument> inputs, outputs;
  file_arguments(request, ToyRequest::fields(), inputs, outputs);
  ASSERT_EQ(inputs.size(), 1u);
  EXPECT_EQ(inputs[0].role, "`source`");
  EXPECT_EQ(inputs[0].path, "s.json");
  request.source = Source{"<source>", "{}"};
  inputs.clear();
  file_arguments(request, ToyRequest::fields(), inputs, outputs);
  EXPECT_TRUE(inputs.empty());
}

TEST(RequestFields, ANameListIsSplitAtCommas) {
  EXPECT_EQ(split_name_list({"theta_i, phi_i", "gamma", ",,"}),
            (std::vector<std::string>{"theta_i", "phi_i", "gamma"}));
  EXPECT_TRUE(split_name_list({}).empty());
}

TEST(RequestFields, AnOutputThatIsAnInputIsRefused) {
  const std::string same = test::scratch_path("request-same.csv");
  const std::string other = test::scratch_path("request-other.csv");
  std::ofstream(same) << "x\n";
  std::ofstream(other) << "y\n";
  ToyRequest request;
  request.input = same;
  request.output = same;
  EXPECT_THROW(check_request_files(request), InputError);
  request.output = other;
  EXPECT_NO_THROW(check_request_files(request));
  // An input found inside another (a formulation's fit file) is protected too.
  EXPECT_THROW(check_request_files(request, {{"`formulation component`", other}}), InputError);
}

}  // namespace
}  // namespace roadbrdf
