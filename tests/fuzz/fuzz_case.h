// The fuzz target's input: bytes -> a mesh and Support Slimming settings (decode), the way back
// for the seed corpus (encode), and one run of the core on it with every result checked
// (run_fuzz_case). The libFuzzer target (slim_fuzz.cpp) and the replay test share them.
//
// The byte format, little-endian, read front to back; whatever runs out reads as zeros, so every
// byte string is an input:
//   u8        flags: 1 TetGen domain, 2 Paper method, 4 rigid-feature bits follow the faces,
//             8 coordinates as float32 (else int8 steps on a grid), 16 two OpenMP threads
//   f32 x 3   print direction        f32  self-supporting angle (deg)   f32  deviation budget (%)
//   i32       voxel resolution       i32  iteration limit               i32  largest K-means k
//   u8        cancel: 0 never, n > 0 the n-th progress report returns false
//   u16       #V, then float mode: #V x f32 x 3;  grid mode: f32 step, f32 x 3 origin, #V x i8 x 3
//   u16       #F, then #F x u16 x 3 vertex indices (not folded: out of range must be refused)
//   bits      one per face, rigid feature or not (flag 4)
// Folding, so that one run stays in milliseconds: #V <= 300, #F <= 600; a resolution in
// [25, 999999] becomes 1 + r % 24 (a million and more stay: the memory guards must refuse them);
// an iteration limit above 3 becomes 1 + n % 3; a largest k above 16 becomes 1 + k % 16.
// Negative and zero values stay as they are: they must be refused.
// Every run gets a 50 MB memory budget (the refusal for more is tested in the core's own tests).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/optimizer/slimming.h"

namespace slim::fuzz {

struct FuzzCase {
  Surface surface;
  SlimmingOptions options;  // only what the format carries is set; progress is not
  int cancel_after = 0;
};

FuzzCase decode(const std::uint8_t* data, size_t size);

// Float mode; decode(encode(c)) gives c back up to float32 rounding and the folding above.
std::vector<std::uint8_t> encode(const FuzzCase& c);

// Runs the case through the core: the overhang analysis, the voxel domain and the embedding, the
// minimal rotation of the mesh's normals, Print Orientation, and Support Slimming (cancelled when
// asked). Returns "" when every outcome is sane: a refusal (std::invalid_argument,
// std::runtime_error, Cancelled) with a one-line reason, or a result that passes
// test::slimming_result_problem and the checks here. Otherwise says what was not. Crashes, leaks and undefined behaviour are the sanitizers'.
std::string run_fuzz_case(const FuzzCase& c);

}  // namespace slim::fuzz
