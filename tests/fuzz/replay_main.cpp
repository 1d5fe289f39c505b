// Runs a fuzz harness over the files of its corpus folder(s) without libFuzzer: `fuzz_replay NAME
// CORPUS...`, the ctest test fuzz_corpus.<name> of every normal build (tests/fuzz/CMakeLists.txt).
// One program holds every harness (harness_table.h), so the harness headers are compiled once.
// Any exception other than the InputError a harness swallows, a crash or (in a sanitized build) a
// sanitizer report fails the test; an empty corpus or an unknown harness also fails, so that a
// moved folder or a harness missing from the table is noticed.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz/harness_table.h"

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  const auto& table = roadbrdf::fuzz::harnesses();
  const auto harness = argc > 1 ? table.find(argv[1]) : table.end();
  if (harness == table.end()) {
    std::fprintf(stderr, "usage: fuzz_replay NAME CORPUS...; unknown harness '%s' (add it to harness_table.h)\n",
                 argc > 1 ? argv[1] : "");
    return 1;
  }
  std::size_t count = 0;
  for (int a = 2; a < argc; ++a) {
    std::vector<fs::path> files;
    if (fs::is_directory(argv[a])) {
      for (const auto& e : fs::directory_iterator(argv[a])) {
        if (e.is_regular_file()) files.push_back(e.path());
      }
    } else {
      files.emplace_back(argv[a]);
    }
    std::sort(files.begin(), files.end());
    for (const auto& file : files) {
      std::ifstream in(file, std::ios::binary);
      const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      std::printf("%s (%zu bytes)\n", file.string().c_str(), bytes.size());
      std::fflush(stdout);
      harness->second(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
      ++count;
    }
  }
  std::printf("%zu inputs, no crash\n", count);
  return count > 0 ? 0 : 1;
}
