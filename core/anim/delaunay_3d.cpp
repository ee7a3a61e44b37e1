#include "core/anim/delaunay_3d.h"

#include <utility>
#include <vector>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include "core/util/error.h"

namespace dfm {

Tetrahedralization delaunay_3d(const Eigen::MatrixXd& X) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Vb = CGAL::Triangulation_vertex_base_with_info_3<int, K>;
  using Cb = CGAL::Triangulation_cell_base_with_info_3<int, K, CGAL::Delaunay_triangulation_cell_base_3<K>>;
  using DT = CGAL::Delaunay_triangulation_3<K, CGAL::Triangulation_data_structure_3<Vb, Cb>>;
  std::vector<std::pair<K::Point_3, int>> pts;
  pts.reserve(X.rows());
  for (int i = 0; i < X.rows(); ++i) pts.push_back({K::Point_3(X(i, 0), X(i, 1), X(i, 2)), i});
  DT dt(pts.begin(), pts.end());
  if (dt.number_of_vertices() != static_cast<size_t>(X.rows())) throw Error("3D Delaunay: two points coincide");
  if (dt.dimension() != 3) throw Error("3D Delaunay: the points are coplanar");
  int n = 0;
  for (auto c = dt.all_cells_begin(); c != dt.all_cells_end(); ++c) c->info() = dt.is_infinite(c) ? -1 : n++;
  Tetrahedralization d;
  d.tets.resize(n, 4);
  d.neighbours.resize(n, 4);
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c)
    for (int j = 0; j < 4; ++j) {
      d.tets(c->info(), j) = c->vertex(j)->info();
      d.neighbours(c->info(), j) = c->neighbor(j)->info();
    }
  return d;
}

}  // namespace dfm
