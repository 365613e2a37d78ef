// Writes the fuzz seed corpora: every case of the bad-input catalogue (support/bad_inputs.h) as
// CORE_DIR/<name>.bin, and the readers' seeds (reader_case.h: the bad-file catalogue and
// well-formed files of each format) as READER_DIR/<name>.bin. tests/fuzz/corpus and
// tests/fuzz/reader_corpus are its output, committed; the replay test checks that they agree.
// Usage: fuzz_corpus_writer CORE_DIR [READER_DIR]
#include <cstdio>
#include <fstream>

#include "fuzz/fuzz_case.h"
#include "support/bad_inputs.h"
#ifdef SLIM_FUZZ_READERS
#include "fuzz/reader_case.h"
#endif

namespace {
bool write(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!out) std::fprintf(stderr, "fuzz_corpus_writer: cannot write %s\n", path.c_str());
  return static_cast<bool>(out);
}
}  // namespace

int main(int argc, char** argv) {
  if (argc != 2 && argc != 3) {
    std::fprintf(stderr, "usage: fuzz_corpus_writer CORE_DIR [READER_DIR]\n");
    return 1;
  }
  for (const slim::test::BadInput& c : slim::test::bad_inputs())
    if (!write(std::string(argv[1]) + "/" + c.name + ".bin", slim::fuzz::encode({c.surface, c.options, 0}))) return 1;
  if (argc == 3) {
#ifdef SLIM_FUZZ_READERS
    for (const auto& [name, bytes] : slim::fuzz::reader_seeds())
      if (!write(std::string(argv[2]) + "/" + name, bytes)) return 1;
#else
    std::fprintf(stderr, "fuzz_corpus_writer: built without the mesh readers (no VCG)\n");
    return 1;
#endif
  }
  return 0;
}
