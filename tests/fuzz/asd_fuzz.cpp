// libFuzzer harness: the asd parser (see instrument_harnesses.h for building and the corpus).
#include "fuzz/instrument_harnesses.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return roadbrdf::fuzz::asd_one_input(data, size);
}
