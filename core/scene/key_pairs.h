#pragma once
// Picked pairs on a document's keys (issue 30): points the artist picks on a key and its partners on
// the next key, which a transition between them sends to each other (transition.h, "The warp").
#include <Eigen/Core>

#include "core/scene/document.h"

namespace dfm {

// The key whose interval holds time t: the last key at or before t (the one before the last key when
// t is at or after it). Throws dfm::Error with fewer than two keys.
int pair_interval(const Document& doc, double t);

// Adds pair (x0 y0 z0 x1 y1 z1) from key `index` to the next as one undo step, after checking it
// against both keys' surfaces as the transition will (transition_pair_problem: each point within 2%
// of its key's bounding-box diagonal; the keys of different connectivity). Throws dfm::Error naming
// the problem; the document is unchanged then.
void add_key_pair(Document& doc, int index, const Eigen::Matrix<double, 1, 6>& pair);

}  // namespace dfm
