#pragma once
// The vertex layouts the surface pass draws: PosNormal, the one every pass writes (transform
// feedback), interleaved position and normal, 6 floats (24 bytes) per vertex; and IntervalVertex.
namespace dfm::gl {

struct PosNormal {
  float position[3];
  float normal[3];
};
static_assert(sizeof(PosNormal) == 24, "PosNormal must be tightly packed");

// One slice vertex of a cached interval of an animation manifold, as shaders/surface.vert.glsl
// (INTERVAL) reads it: the later (up) and earlier (down) endpoint of its manifold edge, their 3D
// slice normals, and mu = A + B (t - t_lo) as (A, B). Attribute locations 0, 3, 1, 4, 5.
struct IntervalVertex {
  float up[3], down[3], n_up[3], n_down[3], mu[2];
};
static_assert(sizeof(IntervalVertex) == 56, "IntervalVertex must be tightly packed");

}  // namespace dfm::gl
