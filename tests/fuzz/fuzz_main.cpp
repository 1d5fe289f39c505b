// The libFuzzer program of -DROADBRDF_FUZZ=ON builds: every harness of harness_table.h in one
// program, linked once. The harness is chosen by the name the program is called by: the build makes
// one link <name>_fuzz per harness (tests/fuzz/CMakeLists.txt), so `alta_fuzz CORPUS` fuzzes the ALTA
// reader. Linking one program instead of one per parser keeps the fuzz build small enough for CI.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "fuzz/harness_table.h"

namespace {

roadbrdf::fuzz::Harness selected_harness = nullptr;

// "…/tests/fuzz/alta_fuzz" → "alta".
std::string harness_name(const char* program) {
  std::string name = program;
  if (const auto slash = name.rfind('/'); slash != std::string::npos) name.erase(0, slash + 1);
  const std::string suffix = "_fuzz";
  if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0) {
    name.resize(name.size() - suffix.size());
  }
  return name;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
  const auto& table = roadbrdf::fuzz::harnesses();
  const std::string name = *argc > 0 ? harness_name((*argv)[0]) : std::string();
  const auto harness = table.find(name);
  if (harness == table.end()) {
    std::fprintf(stderr, "roadbrdf_fuzz: no harness '%s'; call the program as <name>_fuzz, one of:", name.c_str());
    for (const auto& entry : table) std::fprintf(stderr, " %s", entry.first.c_str());
    std::fprintf(stderr, "\n");
    std::exit(1);
  }
  selected_harness = harness->second;
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return selected_harness(data, size);
}
