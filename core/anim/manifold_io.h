#pragma once
// The ".tet4" animation manifold file: plain text, '#' starts a comment line (allowed anywhere).
//
//   tet4 2                      magic and format version (1: without the surfaces and prisms sections)
//   vertices N                  counts
//   tets K
//   layers M                    M >= 2
//   layer T_i FIRST_i           M lines: layer time (strictly increasing) and the first tetrahedron of
//                               slab i (times[i]..times[i+1]); FIRST_0 = 0, the last layer's FIRST = K
//   v X Y Z T                   N lines, 4D vertex positions
//   t A B C D                   K lines, 0-based vertex indices, oriented as in manifold.h
//   surfaces S                  the layers' triangle lists (manifold.h's layer_faces), each as
//   surface NF                    its face count and NF lines
//   f A B C                       of 0-based layer vertex indices
//   prisms P                    P = 0 or one line per slab (manifold.h's PrismSlab):
//   prism FACES LOWER UPPER N     its triangle list (-1: not a prism slab) and layers
//   keys K                      key layers (manifold.h's ManifoldKey), each as
//   key TIME FACES N              its time, triangle list and vertex count, and N lines
//   k V                           of the manifold vertex each key vertex is
//
// Numbers are written with the shortest decimal text that reads back to the same double, so a
// save/load round trip is exact. Loading validates everything (validate_manifold) and throws
// dfm::Error "path:line: problem".
#include <string>

#include "core/anim/manifold.h"

namespace dfm {

void write_manifold(const std::string& path, const AnimationManifold& m);
AnimationManifold read_manifold(const std::string& path);

}  // namespace dfm
