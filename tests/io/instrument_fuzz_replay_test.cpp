// Always-run replay of the instrument fuzz harnesses (tests/fuzz/instrument_harnesses.h) over their
// seed corpora and deterministic mutations of every seed: each truncation, and byte substitutions
// from a fixed pseudo-random sequence. A parser may only reject an input with InputError (caught
// by the harness); any other exception fails here, and a crash ends the test program.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "fuzz/instrument_harnesses.h"
#include "support/paths.h"

namespace roadbrdf {
namespace {

using Harness = int (*)(const std::uint8_t*, std::size_t);

std::vector<std::string> seeds(const std::string& parser) {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(test::generated_corpus_dir() + "/" + parser)) {
    std::ifstream in(e.path(), std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    out.push_back(s.str());
  }
  return out;
}

void replay(const std::string& parser, Harness harness, bool every_truncation) {
  const auto corpus = seeds(parser);
  ASSERT_FALSE(corpus.empty()) << parser;
  std::uint64_t state = 0x9e3779b97f4a7c15ull;
  auto next = [&state] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return state >> 33;
  };
  for (const std::string& seed : corpus) {
    auto run = [&](const std::string& input) {
      EXPECT_NO_THROW(harness(reinterpret_cast<const std::uint8_t*>(input.data()), input.size()));
    };
    run(seed);
    const std::size_t step = every_truncation ? 1 : 7;
    for (std::size_t n = 0; n < seed.size(); n += step) run(seed.substr(0, n));
    for (int k = 0; k < 300; ++k) {
      std::string mutated = seed;
      const int edits = 1 + static_cast<int>(next() % 4);
      for (int e = 0; e < edits && !mutated.empty(); ++e) {
        mutated[next() % mutated.size()] = static_cast<char>(next() & 0xff);
      }
      run(mutated);
    }
  }
}

TEST(InstrumentFuzzReplay, Asd) { replay("asd", fuzz::asd_one_input, true); }
TEST(InstrumentFuzzReplay, Sed) { replay("sed", fuzz::sed_one_input, true); }
TEST(InstrumentFuzzReplay, Sig) { replay("sig", fuzz::sig_one_input, true); }
TEST(InstrumentFuzzReplay, Manifest) { replay("manifest", fuzz::manifest_one_input, false); }

}  // namespace
}  // namespace roadbrdf
