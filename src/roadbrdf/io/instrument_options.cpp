#include "roadbrdf/io/instrument_options.h"

#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/io/instrument.h"

namespace roadbrdf {

RequestFields<InstrumentOptions> InstrumentOptions::fields() {
  using R = InstrumentOptions;
  static const std::string overlap_help = "SVC .sig detector overlap: " + described_names_text<OverlapRule>() +
                                          " (default upper); nothing is averaged, dropped channels are reported";
  static const RequestField<R> rows[] = {
      {"overlap", "--overlap", "", overlap_help, &R::overlap},
  };
  return rows;
}

ManifestOptions InstrumentOptions::manifest_options() const {
  ManifestOptions o;
  o.read.overlap = parse_name<OverlapRule>(overlap, "overlap");
  return o;
}

}  // namespace roadbrdf
