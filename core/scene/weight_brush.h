#pragma once
// The weight brush (Blender's weight paint with auto-normalize): one dab on one handle's column of the
// #V x #handles weights, the rest of each touched row rescaled so that it stays a partition of unity
// (Jacobson 2013, Eq. 4.5-4.6), as weight_normalize.h's rule does.
//
// A vertex at distance r from the dab's centre takes the profile f = brush_weight(r, radius, falloff)
// (core/scene/brush.h's smoothstep) and its painted weight w becomes, clamped to [0, 1]:
//   Add       w + strength f            Subtract  w - strength f
//   Mix       w + strength f (value - w)
//   Smooth    w + strength f (m - w),   m the mean of its edge neighbours' w before the dab
// (a damped Jacobi step on the uniform graph Laplacian: it never raises the column's Dirichlet energy).
// Then the row's other unlocked weights are scaled to sum to 1 - w - (the locked ones' sum). Where the
// locked ones leave less than w, w is lowered to what they leave; where no other unlocked weight is
// positive, w is raised to 1 - locked (nothing else can take the rest). Locked columns and `fixed` rows
// (the bind's constrained vertices, weight_constraints.h) are kept bit for bit.
#include <vector>

#include <Eigen/Core>
#include <Eigen/Sparse>

namespace dfm {

enum class WeightPaintMode { Add, Subtract, Mix, Smooth };

struct WeightBrush {
  WeightPaintMode mode = WeightPaintMode::Add;
  double radius = 0;     // world units, > 0
  double strength = 1;   // [0, 1]
  double falloff = 0.5;  // [0, 1]: the outer fraction of the radius over which the dab fades out
  double value = 1;      // Mix: the weight blended toward, [0, 1]
  // Front faces only: when nonzero, the direction the viewer looks along; a vertex whose normal does
  // not face against it is left alone.
  Eigen::Vector3d facing = Eigen::Vector3d::Zero();
};

// What a dab reads of the surface, built once per surface (the brush runs at the editor's frame rate).
struct WeightPaintSurface {
  Eigen::MatrixXd V;               // #V x 3
  Eigen::MatrixXd N;               // #V x 3 area-weighted unit vertex normals
  Eigen::SparseMatrix<double> K;   // uniform graph Laplacian (surface_laplacian.h's uniform_stiffness)
};
WeightPaintSurface weight_paint_surface(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

struct WeightDab {
  std::vector<int> rows;   // the vertices the dab changed, in index order
  Eigen::MatrixXd values;  // their new rows
};

// locked: #handles flags or empty; fixed: #V flags or empty. Throws dfm::Error for a bad brush, a
// handle out of range or locked, or mismatched sizes.
WeightDab weight_dab(const Eigen::MatrixXd& W, const WeightPaintSurface& surface, int handle, const Eigen::Vector3d& center,
                     const WeightBrush& brush, const std::vector<bool>& locked = {}, const std::vector<bool>& fixed = {});

// Writes the dab's rows into W.
void apply_weight_dab(Eigen::MatrixXd& W, const WeightDab& dab);

}  // namespace dfm
