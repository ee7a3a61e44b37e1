#pragma once
// Translation-rotation-scale: the only local transform glTF can animate.
// A node's matrix is T * R * S; an affine whose linear part has shear cannot be written that way, so
// decompose_trs() returns the closest TRS and how far it is from the input.
#include <Eigen/Geometry>

namespace dfm {

struct Trs {
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  // unit
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
};

struct TrsFit {
  Trs trs;
  // ||L - R*diag(s)||_F / ||L||_F for the linear part L: 0 (to rounding) when M has no shear.
  double shear = 0.0;
};

Eigen::Affine3d compose_trs(const Trs& trs);
// Scale along the axes of R: s_i = |column i of L|, with a negative x scale for a reflection;
// R is the rotation nearest to L * diag(1/s). Throws dfm::Error for a singular or non-finite L.
TrsFit decompose_trs(const Eigen::Affine3d& M);

}  // namespace dfm
