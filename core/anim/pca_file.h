#pragma once
// The ".pca" file: a PcaAnimation (pca_animation.h) in little-endian binary, the triangles once.
//
//   offset  bytes        field
//   0       8            magic "DFMPCA\r\n" (the \r\n catches text-mode copies)
//   8       4            u32 version = 1
//   12      4            u32 V   vertices
//   16      4            u32 T   triangles
//   20      4            u32 N   frames (>= 1)
//   24      4            u32 K   base shapes (<= min(3V, N))
//   28      4            u32 reserved = 0
//   32      12 T         u32 triangles, 3 vertex indices each (< V)
//           12 V         f32 mean, vertex-major (x y z per vertex)
//           12 V K       f32 bases, one after another, each vertex-major (orthonormal)
//           4 N K        f32 coefficients, frame by frame
//           4 N          f32 frame times in seconds (strictly increasing)
//           28 N         f32 rigid motion per frame: rotation quaternion x y z w (unit), translation x y z
//           8            u64 FNV-1a (core/util/hash.h) of every byte before it
//
// Float32 everywhere the error budget allows: positions and bases round at 6e-8 relative, far below
// any base count's reconstruction error; the double decomposition (and the Eckart-Young check) stays in
// memory. Times are float32 as glTF stores them.
#include <cstdint>
#include <string>

#include "core/anim/pca_animation.h"

namespace dfm {

// Writes atomically (core/util/atomic_file.h). Throws dfm::Error naming the path for inconsistent
// sizes, non-finite values or values beyond float32's range.
void write_pca(const std::string& path, const PcaAnimation& a);

// Rejects (dfm::Error naming the file and the problem, with the byte offset where it applies) a wrong
// magic or version, counts the file size does not hold (checked before anything is allocated), a
// checksum mismatch, triangle indices out of range, non-finite values, non-unit quaternions,
// non-increasing times and bases that are not orthonormal.
PcaAnimation read_pca(const std::string& path);

// The exact size of a .pca file with these counts.
std::uint64_t pca_file_bytes(std::uint64_t vertices, std::uint64_t triangles, std::uint64_t frames,
                             std::uint64_t bases);

}  // namespace dfm
