#pragma once
// The Delaunay tetrahedralization of a conforming surface's points (CGAL, exact predicates): its
// vertices, then its fill points; a vertex's info is its index in that order.
#include <optional>
#include <vector>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include "core/anim/conforming_surface.h"

namespace dfm {

using DelaunayKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Delaunay3 = CGAL::Delaunay_triangulation_3<
    DelaunayKernel, CGAL::Triangulation_data_structure_3<
                        CGAL::Triangulation_vertex_base_with_info_3<int, DelaunayKernel>>>;

struct SurfaceDelaunay {
  Delaunay3 dt;
  std::vector<Delaunay3::Vertex_handle> vertex;  // by index: surface vertices, then fill points
};

// Throws dfm::Error when two points coincide.
SurfaceDelaunay surface_delaunay(const ConformingSurface& s);

// surface_delaunay of a surface that grows by appended vertices between calls (make_conforming's
// rounds of edge splits): only the new vertices are inserted, the fill points renumbered after them.
// A point set has one Delaunay tetrahedralization (CGAL breaks ties by symbolic perturbation), so
// the result is surface_delaunay's; any other change of the points rebuilds it.
class GrowingSurfaceDelaunay {
 public:
  // Throws dfm::Error when two points coincide.
  const SurfaceDelaunay& of(const ConformingSurface& s);

 private:
  std::optional<SurfaceDelaunay> d_;
  Eigen::MatrixXd V_, fill_;  // the points d_ holds
};

}  // namespace dfm
