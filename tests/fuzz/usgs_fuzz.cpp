// libFuzzer harness: the USGS splib07a reader (see parser_harnesses.h for building and the corpus).
#include "fuzz/parser_harnesses.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return roadbrdf::fuzz::usgs_one_input(data, size);
}
