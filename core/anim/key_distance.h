#pragma once
// Signed distance to a closed key surface: negative inside, positive outside. The magnitude is the
// distance to the nearest triangle (CGAL's AABB tree); the sign is the generalized winding number's
// (Jacobson 2013, ch. 8: inside where it exceeds 1/2), which stays right near the surface where a
// pseudo-normal test would need exact closest features.
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

  // One value per row of P (#P x 3), computed in parallel.
  Eigen::VectorXd operator()(const Eigen::MatrixXd& P) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dfm
