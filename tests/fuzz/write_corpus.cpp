// Writes the fuzz seed corpus: every case of the bad-input catalogue (support/bad_inputs.h) as
// DIR/<name>.bin. The corpus in tests/fuzz/corpus is its output, committed; the replay test
// checks that they agree. Usage: fuzz_corpus_writer DIR
#include <cstdio>
#include <fstream>

#include "fuzz/fuzz_case.h"
#include "support/bad_inputs.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_corpus_writer DIR\n");
    return 1;
  }
  for (const slim::test::BadInput& c : slim::test::bad_inputs()) {
    const std::vector<std::uint8_t> bytes = slim::fuzz::encode({c.surface, c.options, 0});
    std::ofstream out(std::string(argv[1]) + "/" + c.name + ".bin", std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!out) {
      std::fprintf(stderr, "fuzz_corpus_writer: cannot write %s/%s.bin\n", argv[1], c.name.c_str());
      return 1;
    }
  }
  return 0;
}
