#pragma once
// The relative placement of two keys of a transition (issue 30: a moved key travels, a turned key
// turns): centroid, rotation and uniform scale of the solids, read from their volume moments, and
// its interpolation over the interval (Alexa et al. 2000/2002, 4.1.1: a transformation is
// interpolated through its polar decomposition, the rotation by its angle about its fixed axis, the
// rest linearly; so a half turn is a half turn).
#include <Eigen/Core>

namespace dfm {

// Volume integrals over the solid a closed, outward surface encloses (sums of signed tetrahedra
// from a reference point: the triangulation does not matter, only the solid).
struct SolidMoments {
  double volume = 0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  // Central second moments: integral of (x - centroid)(x - centroid)^T over the solid.
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
};
SolidMoments solid_moments(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// Where key 1 is relative to key 0: a point x of key 0's frame is placed at
//   c1 + scale * R * (x - c0)
// in key 1's. to_source_frame is its inverse, placed_at its interpolation.
struct KeyPlacement {
  Eigen::Vector3d c0 = Eigen::Vector3d::Zero(), c1 = Eigen::Vector3d::Zero();
  double scale = 1;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
};

// The rotation R with R M0 R^T closest to M1 in principal axes (both normalised by their traces),
// the smallest of the candidates that leaves: the principal axes of distinct moments (eigenvalues
// apart by more than 2% of the trace in both) map to each other up to sign; an axis of a repeated
// moment (a solid of revolution, a box's square section) may turn freely, so with one distinct axis
// R is the shortest turn taking it to the other's, with none (a sphere, a cube) R is the identity.
Eigen::Matrix3d principal_rotation(const Eigen::Matrix3d& M0, const Eigen::Matrix3d& M1);

// Centroids, principal_rotation of the second moments, and the ratio of the radii of gyration
// (sqrt(trace(second) / volume)) as scale: a size that holes and handles change little.
KeyPlacement key_placement(const SolidMoments& key0, const SolidMoments& key1);

// Key 1's points (#P x 3) in key 0's frame: c0 + R^T (x - c1) / scale.
Eigen::MatrixXd to_source_frame(const KeyPlacement& p, const Eigen::MatrixXd& X);

// The placement interpolated at u in [0, 1] applied to a point x of key 0's frame:
//   c0 + u (c1 - c0) + ((1 - u) + u scale) R(u) (x - c0),
// R(u) the rotation by u times R's angle about R's axis (Alexa 4.1.1; the scale, the symmetric
// factor of the polar decomposition, linearly). u = 0 returns x itself, u = 1 uses R and scale
// themselves (the inverse of to_source_frame up to rounding).
Eigen::RowVector3d placed_at(const KeyPlacement& p, double u, const Eigen::RowVector3d& x);

}  // namespace dfm
