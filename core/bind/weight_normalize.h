#pragma once
// Normalize with locked handles (Blender's "Normalize All" with locked groups): every row is brought
// back to a partition of unity (Jacobson 2013, Eq. 4.5) by scaling only its unlocked weights.
#include <vector>

#include <Eigen/Core>

namespace dfm {

struct NormalizeReport {
  int rows_scaled = 0;        // rows whose unlocked weights were rescaled
  int rows_locked_over_one = 0;  // locked weights alone sum past 1: unlocked set to 0, row sums to the locked sum
  int rows_without_free_weight = 0;  // locked sum < 1 but no unlocked weight to scale: left as it was
};

// Per row: L = sum of the locked weights, U = sum of the unlocked ones (negative ones clamped to 0 first).
// The unlocked weights are scaled by (1 - L) / U. Where L >= 1 they become 0, as Blender does (the
// locked weights are the user's and never change, so such a row sums to L: the report counts them);
// where U = 0 there is nothing to scale and the row stays. Locked columns and `fixed` rows (#V flags or
// empty) are kept bit for bit. Throws dfm::Error for a locked handle out of range or a size mismatch.
Eigen::MatrixXd normalize_locked(const Eigen::MatrixXd& W, const std::vector<int>& locked,
                                 const std::vector<bool>& fixed = {}, NormalizeReport* report = nullptr);

// #handles flags from a list of handle indices (checked against num_handles).
std::vector<bool> locked_flags(const std::vector<int>& locked, int num_handles);

}  // namespace dfm
