// libFuzzer harness: r-table CSV (see parser_harnesses.h).
#include "fuzz/parser_harnesses.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return roadbrdf::fuzz::rtable_csv_one_input(data, size);
}
