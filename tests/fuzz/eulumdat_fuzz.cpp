// libFuzzer harness: EULUMDAT luminaire files (see luminaire_harnesses.h).
#include "fuzz/luminaire_harnesses.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return roadbrdf::fuzz::eulumdat_one_input(data, size);
}
