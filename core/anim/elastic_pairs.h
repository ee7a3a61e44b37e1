#pragma once
// Alignment by deformation for picked pairs (Southern 2008, 10.1.3; issue 30): the pairs' warp
// (space_warp.h) moves only what the artist picked, so between keys of different shape the rest
// seldom overlaps, and the blend of their distances drops what does not (a teddy sent round a
// ring by its hands, feet and head parts at the belly). Extra pairs close the gap the way
// iterative closest points does, with the pairs' warp as the deformation: points spread over each
// key, each paired with the nearest point of the other (the target as the current warp carries it
// into the source's frame), so that the warp carries the keys' surfaces onto each other and the
// blend handles only what they cannot share (a hole, a handle). Southern 10.1.3 keeps alignment
// rigid because a key deformed before the morph and joined by linear paths self-intersects; here
// the deformation is not applied to a key but to the morph (transition.h: the in-between is
// P_u(W_u(zero set))), and a round is kept only while W_u stays invertible along both keys' paths.
#include <Eigen/Core>

#include "core/anim/space_warp.h"
#include "core/mesh/mesh.h"

namespace dfm {

struct ElasticPairOptions {
  int samples = 16;  // points on each key per round
  int rounds = 2;
  int steps = 8;     // of the warp path (space_warp.h)
};

// Pairs (#pairs x 6: x0 y0 z0 on `source`, x1 y1 z1 on `target`, both in the source's frame) to add
// to the picked ones (`picked`, the same layout) so that the warp through all of them carries the
// target onto the source where they can meet. Samples are farthest points, about diag / sqrt(samples)
// apart (diag: the source's bounding-box diagonal), none within half that of a picked point or of
// each other. A round whose warp would fold space on either key, or fail to invert, is dropped: the
// result is the last round that did not (none: 0 rows). Throws dfm::Error on a bad size or option.
struct ElasticFit {
  Eigen::MatrixXd pairs = Eigen::MatrixXd(0, 6);
  WarpPath warp;            // through the picked pairs and `pairs` (with pairs only)
  Eigen::MatrixXd carried;  // the target's vertices W^-1(v) (with pairs only)
};
ElasticFit elastic_pairs(const TriMesh& source, const TriMesh& target, const Eigen::MatrixXd& picked,
                         const ElasticPairOptions& options = {});

}  // namespace dfm
