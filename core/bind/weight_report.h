#pragma once
// Handles whose weights are zero or nearly zero everywhere (Blender's "Clean" finds the same groups):
// they move nothing, usually because another handle sits on or around them (BBW's locality, Jacobson
// 2013, 4.3.1: an occluded handle gets no influence), or the bind lost them.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/rig/rig.h"

namespace dfm {

struct ZeroWeightHandle {
  int handle = -1;
  std::string name;        // handle_name
  double max_weight = 0;   // its largest weight on any vertex
};

// Every handle (column of W, rig.h order) whose largest weight is below threshold, in handle order.
// Throws dfm::Error when W's columns are not the rig's handles or threshold is not finite.
std::vector<ZeroWeightHandle> zero_weight_report(const Eigen::MatrixXd& W, const Rig& rig, double threshold = 1e-3);

}  // namespace dfm
