#pragma once
// Rotations of point handles inferred from pseudo-edges (Jacobson 2013, sec. 4.3.4): a point handle
// only carries a translation, but the user's pseudo-edges between point handles say how it should
// turn: each handle gets the average of the smallest rotations taking each incident pseudo-edge from
// its rest direction to its posed direction.
#include <utility>
#include <vector>

#include <Eigen/Geometry>

namespace dfm {

// rest, posed: #P x 3 point positions. Returns one rotation per point; points with no usable
// incident pseudo-edge get the identity and has_edge[i] = false (when has_edge is given).
// Zero-length edges (rest or posed) are ignored. Throws dfm::Error on an edge index out of range.
std::vector<Eigen::Quaterniond> pseudo_edge_rotations(const Eigen::MatrixXd& rest, const Eigen::MatrixXd& posed,
                                                      const std::vector<std::pair<int, int>>& edges,
                                                      std::vector<bool>* has_edge = nullptr);

// Normalized sum of unit quaternions, each flipped into the first one's hemisphere (q and -q are the
// same rotation). Identity for an empty list.
Eigen::Quaterniond average_quaternions(const std::vector<Eigen::Quaterniond>& qs);

}  // namespace dfm
