// Every enumeration of the library that has names (core/enum_names.h) against the names this test
// expects, written here value by value in switches without a default: a value added to an
// enumeration fails to compile here (-Wswitch) until it is given its name, and then fails the test
// until its table names it too. Each table must hold each value once, under the expected name, and
// nothing else; every name must parse back to its value.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/fitting/fit.h"
#include "roadbrdf/fitting/params_table.h"
#include "roadbrdf/formulation/formulation.h"
#include "roadbrdf/io/alta.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/geometry_file.h"
#include "roadbrdf/io/instrument.h"
#include "roadbrdf/lighting/installation.h"
#include "roadbrdf/lighting/luminaire.h"
#include "roadbrdf/mixing/mixing.h"
#include "roadbrdf/models/mixture_model.h"
#include "roadbrdf/photometry/rtable.h"
#include "roadbrdf/photometry/rtable_io.h"
#include "roadbrdf/surface/render.h"

namespace roadbrdf {
namespace {

using lighting::Arrangement;
using lighting::PhotometricSymmetry;
using lighting::RoadSide;
using mixing::Method;
using mixing::MixtureKind;
using photometry::ClassSystem;
using photometry::Q0Region;
using photometry::RTableFormat;
using surface::Sampling;

// The expected names. "" for a number that is no value of the enumeration.
std::string_view expected(FitLoss v) {
  switch (v) {
    case FitLoss::kPlain:
      return "plain";
    case FitLoss::kRelative:
      return "relative";
    case FitLoss::kLog:
      return "log";
    case FitLoss::kCosine:
      return "cosine";
  }
  return "";
}
std::string_view expected(RobustLoss v) {
  switch (v) {
    case RobustLoss::kNone:
      return "none";
    case RobustLoss::kHuber:
      return "huber";
    case RobustLoss::kCauchy:
      return "cauchy";
  }
  return "";
}
std::string_view expected(JointSolver v) {
  switch (v) {
    case JointSolver::kDenseSchur:
      return "dense-schur";
    case JointSolver::kSparseSchur:
      return "sparse-schur";
    case JointSolver::kIterativeSchur:
      return "iterative-schur";
  }
  return "";
}
std::string_view expected(ParamsFormat v) {
  switch (v) {
    case ParamsFormat::kTable:
      return "table";
    case ParamsFormat::kCsv:
      return "csv";
    case ParamsFormat::kMarkdown:
      return "markdown";
    case ParamsFormat::kLatex:
      return "latex";
  }
  return "";
}
std::string_view expected(DatasetFormat v) {
  switch (v) {
    case DatasetFormat::kWide:
      return "wide";
    case DatasetFormat::kLong:
      return "long";
  }
  return "";
}
std::string_view expected(AngleConvention v) {
  switch (v) {
    case AngleConvention::kZenithAzimuth:
      return "zenith";
    case AngleConvention::kRoad:
      return "road";
  }
  return "";
}
std::string_view expected(AltaOutput v) {
  switch (v) {
    case AltaOutput::kInvSteradian:
      return "INV_STERADIAN";
    case AltaOutput::kInvSteradianCosine:
      return "INV_STERADIAN_COSINE_FACTOR";
  }
  return "";
}
std::string_view expected(InstrumentFormat v) {
  switch (v) {
    case InstrumentFormat::kAsd:
      return "asd";
    case InstrumentFormat::kSed:
      return "sed";
    case InstrumentFormat::kSig:
      return "sig";
  }
  return "";
}
std::string_view expected(OverlapRule v) {
  switch (v) {
    case OverlapRule::kUpper:
      return "upper";
    case OverlapRule::kLower:
      return "lower";
    case OverlapRule::kError:
      return "error";
  }
  return "";
}
std::string_view expected(InstrumentQuantity v) {
  switch (v) {
    case InstrumentQuantity::kTarget:
      return "target";
    case InstrumentQuantity::kReference:
      return "reference";
    case InstrumentQuantity::kReflectance:
      return "reflectance";
  }
  return "";
}
std::string_view expected(ComponentKind v) {
  switch (v) {
    case ComponentKind::kBinder:
      return "binder";
    case ComponentKind::kAggregate:
      return "aggregate";
    case ComponentKind::kFiller:
      return "filler";
    case ComponentKind::kPigment:
      return "pigment";
  }
  return "";
}
std::string_view expected(PhotometricSymmetry v) {
  switch (v) {
    case PhotometricSymmetry::none:
      return "none";
    case PhotometricSymmetry::rotational:
      return "rotational";
    case PhotometricSymmetry::c0_c180:
      return "c0-c180";
    case PhotometricSymmetry::c90_c270:
      return "c90-c270";
    case PhotometricSymmetry::quadrants:
      return "quadrants";
  }
  return "";
}
std::string_view expected(Arrangement v) {
  switch (v) {
    case Arrangement::single_sided:
      return "single-sided";
    case Arrangement::staggered:
      return "staggered";
    case Arrangement::opposite:
      return "opposite";
    case Arrangement::twin_central:
      return "twin-central";
  }
  return "";
}
std::string_view expected(RoadSide v) {
  switch (v) {
    case RoadSide::right:
      return "right";
    case RoadSide::left:
      return "left";
  }
  return "";
}
std::string_view expected(MixtureKind v) {
  switch (v) {
    case MixtureKind::kLinear:
      return "linear";
    case MixtureKind::kHapke:
      return "hapke";
    case MixtureKind::kShadowed:
      return "shadowed";
  }
  return "";
}
std::string_view expected(Method v) {
  switch (v) {
    case Method::kAreal:
      return "areal";
    case Method::kFitted:
      return "fitted";
    case Method::kMastic:
      return "mastic";
    case Method::kHapke:
      return "hapke";
    case Method::kShadowed:
      return "shadowed";
  }
  return "";
}
std::string_view expected(Q0Region v) {
  switch (v) {
    case Q0Region::standard:
      return "standard";
    case Q0Region::table:
      return "table";
  }
  return "";
}
std::string_view expected(ClassSystem v) {
  switch (v) {
    case ClassSystem::R:
      return "R";
    case ClassSystem::N:
      return "N";
    case ClassSystem::C:
      return "C";
  }
  return "";
}
std::string_view expected(RTableFormat v) {
  switch (v) {
    case RTableFormat::csv:
      return "csv";
    case RTableFormat::rtb:
      return "rtb";
    case RTableFormat::radiance:
      return "radiance";
  }
  return "";
}
std::string_view expected(Sampling v) {
  switch (v) {
    case Sampling::cosine:
      return "cosine";
    case Sampling::brdf:
      return "brdf";
  }
  return "";
}

// The enumerations have the default values 0, 1, ...: the values are the numbers from 0 that
// `expected` names.
template <typename Enum>
std::vector<Enum> expected_values() {
  std::vector<Enum> values;
  for (int k = 0; !expected(static_cast<Enum>(k)).empty(); ++k) values.push_back(static_cast<Enum>(k));
  return values;
}

template <typename Enum>
void expect_complete_table(const char* enumeration) {
  SCOPED_TRACE(enumeration);
  const std::vector<Enum> values = expected_values<Enum>();
  ASSERT_GE(values.size(), 2U);
  const std::span<const EnumName<Enum>> table = names_table<Enum>();
  EXPECT_EQ(table.size(), values.size()) << "the table misses a value or holds one twice";
  std::set<std::string_view> names;
  std::set<int> numbers;
  for (const EnumName<Enum>& entry : table) {
    names.insert(entry.name);
    numbers.insert(static_cast<int>(entry.value));
    EXPECT_FALSE(expected(entry.value).empty()) << "the table holds " << static_cast<int>(entry.value);
  }
  EXPECT_EQ(names.size(), table.size()) << "two values share a name";
  EXPECT_EQ(numbers.size(), table.size()) << "a value is named twice";
  for (Enum value : values) {
    const std::string name(expected(value));
    EXPECT_EQ(name_of(value), name);
    EXPECT_EQ(parse_name<Enum>(name, "field"), value) << name;
  }
  try {
    parse_name<Enum>("not-a-name", "some.field");
    ADD_FAILURE() << "no error";
  } catch (const FieldError& e) {
    EXPECT_EQ(e.field(), "some.field");
    // The names listed are the expected ones (in the table's order, which the test leaves free).
    const std::string prefix = "'not-a-name' is not one of ";
    ASSERT_EQ(e.detail().rfind(prefix, 0), 0U) << e.detail();
    std::set<std::string> listed;
    std::string rest = e.detail().substr(prefix.size());
    for (std::size_t comma; (comma = rest.find(", ")) != std::string::npos; rest = rest.substr(comma + 2)) {
      listed.insert(rest.substr(0, comma));
    }
    listed.insert(rest);
    std::set<std::string> wanted;
    for (Enum value : values) wanted.insert(std::string(expected(value)));
    EXPECT_EQ(listed, wanted) << e.detail();
  }
}

TEST(EnumTables, EveryTableNamesEveryValueOnceAndNothingElse) {
  expect_complete_table<FitLoss>("FitLoss");
  expect_complete_table<RobustLoss>("RobustLoss");
  expect_complete_table<JointSolver>("JointSolver");
  expect_complete_table<ParamsFormat>("ParamsFormat");
  expect_complete_table<DatasetFormat>("DatasetFormat");
  expect_complete_table<AngleConvention>("AngleConvention");
  expect_complete_table<AltaOutput>("AltaOutput");
  expect_complete_table<InstrumentFormat>("InstrumentFormat");
  expect_complete_table<OverlapRule>("OverlapRule");
  expect_complete_table<InstrumentQuantity>("InstrumentQuantity");
  expect_complete_table<ComponentKind>("ComponentKind");
  expect_complete_table<MixtureKind>("MixtureKind");
  expect_complete_table<Method>("mixing::Method");
  expect_complete_table<Q0Region>("photometry::Q0Region");
  expect_complete_table<ClassSystem>("photometry::ClassSystem");
  expect_complete_table<RTableFormat>("photometry::RTableFormat");
  expect_complete_table<Sampling>("surface::Sampling");
  expect_complete_table<PhotometricSymmetry>("lighting::PhotometricSymmetry");
  expect_complete_table<Arrangement>("lighting::Arrangement");
  expect_complete_table<RoadSide>("lighting::RoadSide");
}

TEST(EnumTables, AnErrorNamesTheFieldTheNamesAndTheNearestName) {
  try {
    parse_name<JointSolver>("dense-shur", "joint_solver");
    ADD_FAILURE() << "no error";
  } catch (const FieldError& e) {
    EXPECT_STREQ(e.what(),
                 "joint_solver: 'dense-shur' is not one of dense-schur, sparse-schur, iterative-schur (did you mean "
                 "'dense-schur'?)");
  }
}

// The parsers that accept more than the exact names: the letter case (losses, class systems, r-table
// formats), a robust loss's scale, and the Radiance file's extension as a format.
TEST(EnumTables, ParsersWithMoreSpellingsUseTheSameNames) {
  EXPECT_EQ(fit_loss_from_string("LOG"), FitLoss::kLog);
  RobustLoss robust = RobustLoss::kNone;
  double scale = 0.0;
  robust_loss_from_string("Cauchy:0.5", robust, scale);
  EXPECT_EQ(robust, RobustLoss::kCauchy);
  EXPECT_EQ(scale, 0.5);
  robust_loss_from_string("", robust, scale);
  EXPECT_EQ(robust, RobustLoss::kNone);
  EXPECT_EQ(photometry::class_system_from_name("n"), ClassSystem::N);
  EXPECT_EQ(photometry::rtable_format_from_name("DAT"), RTableFormat::radiance);
  try {
    robust_loss_from_string("hubber:1", robust, scale);
    ADD_FAILURE() << "no error";
  } catch (const FieldError& e) {
    EXPECT_STREQ(e.what(), "robust: 'hubber' is not one of none, huber, cauchy (did you mean 'huber'?)");
  }
  try {
    photometry::rtable_format_from_name("rtbx", "import_format");
    ADD_FAILURE() << "no error";
  } catch (const FieldError& e) {
    EXPECT_STREQ(e.what(), "import_format: 'rtbx' is not one of csv, rtb, radiance (did you mean 'rtb'?)");
  }
}

}  // namespace
}  // namespace roadbrdf
