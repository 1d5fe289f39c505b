// libFuzzer harness: ASAM OpenMATERIAL 3D BRDF look-up tables (see openmaterial3d_harness.h).
#include "fuzz/openmaterial3d_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return roadbrdf::fuzz::openmaterial3d_one_input(data, size);
}
