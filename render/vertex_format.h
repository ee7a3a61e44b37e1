#pragma once
// The one vertex layout every pass writes (transform feedback) and the surface pass draws:
// interleaved position and normal, 6 floats (24 bytes) per vertex.
namespace dfm::gl {

struct PosNormal {
  float position[3];
  float normal[3];
};
static_assert(sizeof(PosNormal) == 24, "PosNormal must be tightly packed");

}  // namespace dfm::gl
