// The fuzz targets' inputs in the ordinary test suite: every seed of fuzz/corpus/<target>/ and
// every input that once found a defect, fuzz/regressions/<target>/ (kept, with the defect fixed;
// docs/fuzzing.md), run through the same target functions the fuzzers run, so that each stays
// fixed in every build, with or without clang. An input that crashes, trips a sanitizer or throws
// what the target does not document fails here.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_targets.hpp"

namespace dentsph {
namespace {

namespace fs = std::filesystem;

struct Target {
  const char* name;
  int (*run)(const std::uint8_t*, std::size_t);
};

const Target kTargets[] = {
    {"scene", fuzz::scene},       {"procedure", fuzz::procedure}, {"recording", fuzz::recording},
    {"mesh", fuzz::mesh},         {"protocol", fuzz::protocol},   {"store_address", fuzz::store_address},
    {"report_folder", fuzz::report_folder}, {"realtime_options", fuzz::realtime_options},
#ifdef DENTSPH_FUZZ_HAVE_VIEWER
    {"input_script", fuzz::input_script},
#endif
};

std::vector<fs::path> inputs(const fs::path& dir) {
  std::vector<fs::path> files;
  std::error_code ec;
  if (fs::is_directory(dir, ec))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file() && e.path().filename().string()[0] != '.') files.push_back(e.path());
  return files;
}

std::vector<std::uint8_t> bytes_of(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// One test per target, so that a slow build (the sanitizers') has each target's own time limit;
// an input taking over a second is named in the output.
class FuzzInputs : public ::testing::TestWithParam<Target> {};

TEST_P(FuzzInputs, EverySeedAndEveryFoundDefectRunsClean) {
  const Target& t = GetParam();
  const std::vector<fs::path> seeds = inputs(fs::path("fuzz/corpus") / t.name);
  EXPECT_FALSE(seeds.empty()) << "fuzz/corpus/" << t.name << " (tests run from the repository root)";
  std::vector<fs::path> all = seeds;
  const std::vector<fs::path> regressions = inputs(fs::path("fuzz/regressions") / t.name);
  all.insert(all.end(), regressions.begin(), regressions.end());
  for (const fs::path& f : all) {
    const std::vector<std::uint8_t> data = bytes_of(f);
    const auto start = std::chrono::steady_clock::now();
    EXPECT_NO_THROW(EXPECT_EQ(t.run(data.data(), data.size()), 0)) << f;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (s > 1) std::printf("%s: %.1f s\n", f.string().c_str(), s);
  }
  std::printf("%s: %zu seeds, %zu regression inputs\n", t.name, seeds.size(), regressions.size());
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzInputs, ::testing::ValuesIn(kTargets),
                         [](const ::testing::TestParamInfo<Target>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace dentsph
