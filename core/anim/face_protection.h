#pragma once
// Keeps a conforming surface conforming while points are added (fill, chord cover). The spheres
// through a triangle's corners form a pencil, their centres on the normal through its circumcentre at
// signed offsets s; where the triangle is a Delaunay face, the empty ones are those with s between
// the circumspheres of its two Delaunay cells. A new point on the triangle's positive side lies in
// the spheres above some offset, on its negative side in those below one: it narrows the range. A
// point is admitted only while every triangle keeps a range, so every protected triangle stays a
// Delaunay face whatever else is admitted. This widens the encroachment rule of Southern 2008, 5.1.3
// and 7.6.2 (a point inside a facet's diametral sphere encroaches it): the diametral sphere is one
// sphere of the pencil, and a point that enters it need not empty the whole range.
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/anim/surface_delaunay.h"

namespace dfm {

// The centre of the circle through a, b and c (not finite for collinear corners).
Eigen::RowVector3d circumcentre(const Eigen::RowVector3d& a, const Eigen::RowVector3d& b, const Eigen::RowVector3d& c);

class FaceProtection {
 public:
  // Protects each triangle of s that is a face of d (d: surface_delaunay(s)); keeps points away from
  // the others.
  FaceProtection(const ConformingSurface& s, const SurfaceDelaunay& d);

  // Whether adding p leaves every protected triangle an empty sphere (with a margin of 1e-6 of its
  // circumradius, so no new point is co-spherical with one); if so and commit is set, the ranges
  // narrow by p.
  bool admit(const Eigen::RowVector3d& p, bool commit = true);

 private:
  struct Face {
    Eigen::RowVector3d centre, normal;  // circumcentre, unit normal
    double R2 = 0, lo = 0, hi = 0;      // squared circumradius; the range of empty offsets
    int row = -1;                       // in s.F
    // Not a Delaunay face: no point is admitted within twice its circumradius of its circumcentre.
    bool missing = false;
  };
  // Calls visit(face index) for every face whose spheres may hold p, until it returns false; returns
  // whether it never did.
  template <class Visit>
  bool visit_near(const Eigen::RowVector3d& p, const Visit& visit) const;
  // f's range once p is added (empty: lo > hi).
  static std::pair<double, double> narrowed(const Face& f, const Eigen::RowVector3d& p);

  std::vector<Face> faces_;
  double cell_ = 1;
  std::unordered_map<std::uint64_t, std::vector<int>> grid_;  // faces by the grid cells their spheres reach
  std::vector<int> large_;                                    // faces whose spheres reach too many cells
};

}  // namespace dfm
