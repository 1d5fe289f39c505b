// libFuzzer entry point of the ASAM OpenMATERIAL 3D reader (io/openmaterial3d.h), read as a dataset
// with and without missing values and averaged duplicates allowed (see parser_harnesses.h).
#pragma once

#include "fuzz/parser_harnesses.h"
#include "roadbrdf/io/openmaterial3d.h"

namespace roadbrdf::fuzz {

inline int openmaterial3d_one_input(const std::uint8_t* data, std::size_t size) {
  const ScratchFile file("data_brdf.xompt", bytes(data, size));
  for (bool lenient : {false, true}) {
    DatasetReadOptions o;
    o.allow_missing = lenient;
    o.average_duplicates = lenient;
    o.warn = quiet;
    DatasetReadStats stats;
    refusing([&] { read_openmaterial3d(file.path(), o, stats); });
  }
  return 0;
}

}  // namespace roadbrdf::fuzz
