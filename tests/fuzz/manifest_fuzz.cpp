// libFuzzer harness: the manifest parser (see instrument_harnesses.h for building and the corpus).
#include "fuzz/instrument_harnesses.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return roadbrdf::fuzz::manifest_one_input(data, size);
}
