// Every committed fuzz input runs in the ordinary test suite (and under the sanitizers): for the
// core, the seed corpus (the bad-input catalogue as bytes) and the regressions (inputs the fuzzer
// once crashed on, kept after the fix); for the mesh readers, their seed corpus (the bad-file
// catalogue and well-formed files) and their regressions.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "fuzz/fuzz_case.h"
#include "support/bad_inputs.h"
#include "support/source_paths.h"
#ifdef SLIM_FUZZ_READERS
#include "fuzz/reader_case.h"
#include "mesh_io/mesh_io.h"
#endif

namespace fs = std::filesystem;

namespace {
const fs::path kFuzzDir = fs::path(slim::test::source_dir()) / "tests" / "fuzz";

std::vector<std::uint8_t> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::vector<std::string> committed_inputs(std::initializer_list<const char*> dirs) {
  std::vector<std::string> names;
  for (const char* dir : dirs)
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

std::string test_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param;
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Committed, FuzzInput, ::testing::ValuesIn(committed_inputs({"corpus", "regressions"})), test_name);

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

#ifdef SLIM_FUZZ_READERS
namespace {
class ReaderFuzzInput : public ::testing::TestWithParam<std::string> {};
}  // namespace

TEST_P(ReaderFuzzInput, ReadsSanely) {
  const std::vector<std::uint8_t> bytes = read_bytes(kFuzzDir / GetParam());
  EXPECT_EQ(slim::fuzz::run_reader_case(bytes.data(), bytes.size()), "") << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Committed, ReaderFuzzInput,
                         ::testing::ValuesIn(committed_inputs({"reader_corpus", "reader_regressions"})), test_name);

TEST(ReaderFuzzCorpus, HoldsEverySeed) {
  // Regenerate with: fuzz_corpus_writer tests/fuzz/corpus tests/fuzz/reader_corpus
  for (const auto& [name, bytes] : slim::fuzz::reader_seeds()) {
    const fs::path file = kFuzzDir / "reader_corpus" / name;
    ASSERT_TRUE(fs::exists(file)) << file;
    EXPECT_EQ(read_bytes(file), bytes) << file << " is out of date";
  }
}

TEST(ReaderFuzzCase, EveryBadFileIsRefusedAndEveryValidSeedReads) {
  // The seeds are what they say: a bad file is refused, a valid one reads (and run_reader_case,
  // above, finds both outcomes sane: the valid ones round-trip).
  const char* const extensions[4] = {"ply", "stl", "obj", "off"};
  for (const auto& [name, bytes] : slim::fuzz::reader_seeds()) {
    const std::string file = std::string("seed.") + extensions[bytes.at(0) % 4];
    const std::string contents(bytes.begin() + 1, bytes.end());
    if (name.rfind("valid_", 0) == 0) {
      EXPECT_NO_THROW(slim::io::parse_mesh(file, contents)) << name;
    } else {
      EXPECT_THROW(slim::io::parse_mesh(file, contents), std::runtime_error) << name;
    }
  }
  const std::uint8_t empty_stl = 1;
  EXPECT_EQ(slim::fuzz::run_reader_case(&empty_stl, 1), "");
}
#endif
