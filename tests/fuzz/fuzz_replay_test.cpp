// Every committed fuzz input runs in the ordinary test suite (and under the sanitizers): the seed
// corpus (the bad-input catalogue as bytes) and the regressions (inputs the fuzzer once crashed
// on, kept after the fix).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "fuzz/fuzz_case.h"
#include "support/bad_inputs.h"

namespace fs = std::filesystem;

namespace {
const fs::path kFuzzDir = fs::path(SLIM_SOURCE_DIR) / "tests" / "fuzz";

std::vector<std::uint8_t> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::vector<std::string> committed_inputs() {
  std::vector<std::string> names;
  for (const char* dir : {"corpus", "regressions"})
    for (const auto& entry : fs::directory_iterator(kFuzzDir / dir))
      if (entry.is_regular_file() && entry.path().filename() != "README.md")
        names.push_back(std::string(dir) + "/" + entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

class FuzzInput : public ::testing::TestWithParam<std::string> {};
}  // namespace

TEST_P(FuzzInput, RunsSanely) {
  const std::vector<std::uint8_t> bytes = read_bytes(kFuzzDir / GetParam());
  EXPECT_EQ(slim::fuzz::run_fuzz_case(slim::fuzz::decode(bytes.data(), bytes.size())), "") << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Committed, FuzzInput, ::testing::ValuesIn(committed_inputs()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           for (char& ch : name)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return name;
                         });

TEST(FuzzCorpus, HoldsEveryCaseOfTheCatalogue) {
  // Regenerate with: fuzz_corpus_writer tests/fuzz/corpus
  for (const slim::test::BadInput& c : slim::test::bad_inputs()) {
    const fs::path file = kFuzzDir / "corpus" / (c.name + ".bin");
    ASSERT_TRUE(fs::exists(file)) << file;
    EXPECT_EQ(read_bytes(file), slim::fuzz::encode({c.surface, c.options, 0})) << file << " is out of date";
  }
}

TEST(FuzzCase, DecodesWhatItEncodes) {
  for (const slim::test::BadInput& c : slim::test::bad_inputs()) {
    const std::vector<std::uint8_t> bytes = slim::fuzz::encode({c.surface, c.options, 0});
    const slim::fuzz::FuzzCase back = slim::fuzz::decode(bytes.data(), bytes.size());
    EXPECT_EQ(back.surface.F, c.surface.F) << c.name;
    EXPECT_TRUE(back.surface.V.cast<float>().cwiseEqual(c.surface.V.cast<float>()).all() ||
                !c.surface.V.allFinite()) << c.name;
    EXPECT_EQ(back.options.rigid_features, c.options.rigid_features) << c.name;
    EXPECT_EQ(back.options.resolution, c.options.resolution) << c.name;
  }
  // Short inputs read as zeros: a valid, refused case, not a crash.
  const std::uint8_t one = 8;
  EXPECT_EQ(slim::fuzz::run_fuzz_case(slim::fuzz::decode(&one, 1)), "");
}
