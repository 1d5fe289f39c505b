// libFuzzer harness: installation files (see installation_harnesses.h).
#include "fuzz/installation_harnesses.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return roadbrdf::fuzz::installation_one_input(data, size);
}
