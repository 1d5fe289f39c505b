// libFuzzer harness: spectrum files (see parser_harnesses.h).
#include "fuzz/parser_harnesses.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return roadbrdf::fuzz::spectrum_one_input(data, size);
}
