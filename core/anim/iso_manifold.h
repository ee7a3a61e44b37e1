#pragma once
// The zero level set of a piecewise linear field over a 4D triangulation ("marching pentatopes"):
// in each 4-simplex the field is linear, so its zero set is a flat convex polytope, a tetrahedron
// (one corner on one side) or a triangular prism (two and three), cut into tetrahedra by a rule on
// global vertex numbers (Dompierre et al. 1999: each quadrilateral takes the diagonal from its
// smallest vertex) so that neighbouring simplices meet without cracks. Because every 4-simplex is
// cut by one rule of signs, the result is a closed 3-manifold wherever the field is nonzero at the
// vertices: no repair is needed.
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "core/anim/delaunay_4d.h"
#include "core/anim/manifold.h"

namespace dfm {

struct IsoField {
  MatrixX4dRow points;     // the triangulated points (x, y, z, t)
  Eigen::VectorXd values;  // the field at each point, never 0
  // Per point whether it is anchored: an anchored point (its value negative) stands for the level
  // set where it is, so every crossing on an edge from it is the point itself (a key's surface
  // vertex: locally the level set is the cone from it, as if its value were 0).
  std::vector<char> anchored;
};

struct IsoManifold {
  MatrixX4dRow V;                // crossing points
  MatrixX4iRow T;                // tetrahedra, 4D normals toward positive values (manifold.h)
};

// Throws dfm::Error when a value is 0 or not finite or the sizes disagree.
IsoManifold iso_manifold(const IsoField& field, const Delaunay4& D);

// The same, given the simplices part by part (a caller cuts those it has while others are still
// being built): the result is iso_manifold's over the parts in their order. Each part's field
// extends the last one's (the same points and values where both have them); finish takes the last.
class IsoManifoldBuilder {
 public:
  IsoManifoldBuilder();
  ~IsoManifoldBuilder();
  // Throws as iso_manifold does.
  void add(const IsoField& field, const MatrixX5iRow& simplices);
  IsoManifold finish(const IsoField& field);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dfm
