// Load speed of the dataset readers: a wide CSV of 2151 wavelengths (350-2500 nm, 1 nm) x 10^4
// geometries (about 21.5 million values, ~200 MB), as the issue asks for ("well under a second").
// Run: build/bench/dataset_io_bench --benchmark_filter=ReadWide
#include <benchmark/benchmark.h>

#include <filesystem>
#include <random>

#include "roadbrdf/io/dataset_io.h"

namespace {

const std::string& big_file() {
  static const std::string path = [] {
    const std::string p = (std::filesystem::temp_directory_path() / "roadbrdf_bench_2151x10000.csv").string();
    roadbrdf::SpectralDataset d;
    for (int k = 0; k < 2151; ++k) d.wavelengths.push_back(350.0 + k);
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> u(0.0, 0.3);
    for (int g = 0; g < 10000; ++g) {
      d.geometries.push_back(roadbrdf::geometry_from_degrees(0.5 + 0.8 * (g % 100), 0.0, 0.5 + 0.8 * (g / 100), 180.0));
    }
    d.brdf.resize(d.geometries.size() * d.wavelengths.size());
    // Values with 6 significant digits, as instruments write them.
    for (auto& v : d.brdf) v = std::round(u(rng) * 1e6) / 1e6;
    roadbrdf::write_dataset(d, p);
    return p;
  }();
  return path;
}

void ReadWide(benchmark::State& state) {
  const std::string& path = big_file();
  for (auto _ : state) {
    roadbrdf::SpectralDataset d = roadbrdf::read_dataset(path);
    benchmark::DoNotOptimize(d.brdf.data());
  }
  state.counters["file_MB"] = static_cast<double>(std::filesystem::file_size(path)) / 1e6;
  state.counters["values"] = 2151.0 * 10000.0;
}
BENCHMARK(ReadWide)->Unit(benchmark::kMillisecond)->Iterations(3);

void WriteWide(benchmark::State& state) {
  const roadbrdf::SpectralDataset d = roadbrdf::read_dataset(big_file());
  const std::string out = big_file() + ".out.csv";
  for (auto _ : state) roadbrdf::write_dataset(d, out);
  std::filesystem::remove(out);
}
BENCHMARK(WriteWide)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace
