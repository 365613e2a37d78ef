// The mesh readers' fuzz input and checks, shared by the libFuzzer target (reader_fuzz.cpp), the
// seed-corpus writer and the replay test.
//
// The byte format: byte 0 picks the format by its value mod 4 (0 PLY, 1 STL, 2 OBJ, 3 OFF); the
// rest is the file, parsed as it is (vcg_adapters/mesh_io.h: parse_mesh). An empty input reads
// as an empty PLY file.
//
// run_reader_case(bytes) -> "" when the outcome is sane, else what is not. Sane is either
//   a refusal: a std::runtime_error whose message is one line and starts "cannot read <name>: ", or
//   a mesh: faces within its vertices, every attribute empty or one row per vertex (face), and,
//   when its coordinates are finite, written back in its own format and read again it gives the
//   same vertex list, face list and attributes (what the format stores: STL corners as floats,
//   PLY texture coordinates as floats). Crashes, leaks and undefined behaviour are the
//   sanitizers' to report; an allocation beyond libFuzzer's -rss_limit_mb is a finding too.
//
// reader_seeds() -> the seed corpus: every file of the bad-file catalogue (support/bad_inputs.h)
//   and well-formed files of each format and encoding (ASCII and binary PLY, both endians; ASCII
//   and binary STL; OBJ with texture coordinates, normals, colours and a polygon; OFF with
//   normals and colours), as (file name, fuzz input).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace slim::fuzz {

std::string run_reader_case(const std::uint8_t* data, size_t size);

std::vector<std::uint8_t> encode_reader_case(const std::string& extension, const std::string& file_bytes);

std::vector<std::pair<std::string, std::vector<std::uint8_t>>> reader_seeds();

}  // namespace slim::fuzz
