// libFuzzer harness: cross-section calibration files (JSON, mix-calibrate) (see parser_harnesses.h).
#include "fuzz/parser_harnesses.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return roadbrdf::fuzz::cross_sections_one_input(data, size);
}
