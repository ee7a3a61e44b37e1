#pragma once
// Signed distance to a closed key surface: negative inside, positive outside. The magnitude is the
// distance to the nearest triangle (CGAL's AABB tree). The sign is the side of the nearest feature's
// angle-weighted pseudo-normal (Baerentzen and Aanaes 2005: exact for a closed, oriented surface)
// where the point lies clearly off the surface along it (the offset's component along the normal at
// least a tenth of its length); elsewhere, near the surface or nearly along it, where reading the
// nearest feature wrongly would flip the sign, the generalized winding number's (Jacobson 2013,
// ch. 8: inside where it exceeds 1/2; test_key_distance compares the signs). The pseudo-normal is
// the cheaper of the two: it comes with the nearest-point query.
#include <memory>

#include <Eigen/Core>

namespace dfm {

class SignedDistance {
 public:
  // V, F: a closed, outward surface (not checked here; see check_transition_key).
  SignedDistance(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);
  ~SignedDistance();
  SignedDistance(SignedDistance&&) noexcept;
  SignedDistance& operator=(SignedDistance&&) noexcept;

  // One value per row of P (#P x 3), computed in parallel. With `gradient`, also d's gradient there
  // (#P x 3): the unit vector from the nearest surface point, times d's sign (on the surface, the
  // pseudo-normal's direction).
  Eigen::VectorXd operator()(const Eigen::MatrixXd& P, Eigen::MatrixXd* gradient = nullptr) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dfm
