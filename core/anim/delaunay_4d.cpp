#include "core/anim/delaunay_4d.h"

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include <CGAL/Delaunay_triangulation.h>
#include <CGAL/Epick_d.h>
#include <CGAL/Triangulation_data_structure.h>
#include <CGAL/Triangulation_full_cell.h>
#include <CGAL/Triangulation_vertex.h>

#include "core/util/error.h"

namespace dfm {

namespace {

using K4 = CGAL::Epick_d<CGAL::Dimension_tag<4>>;
using Vertex4 = CGAL::Triangulation_vertex<K4, int>;
using Cell4 = CGAL::Triangulation_full_cell<K4, int>;
using Tds4 = CGAL::Triangulation_data_structure<CGAL::Dimension_tag<4>, Vertex4, Cell4>;
using DT4 = CGAL::Delaunay_triangulation<K4, Tds4>;

using Coords = std::array<double, 4>;

Coords coords_of(const K4::Point_d& p) { return {p[0], p[1], p[2], p[3]}; }

}  // namespace

Delaunay4 delaunay_4d(const Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>& P) {
  const int n = static_cast<int>(P.rows());
  std::vector<K4::Point_d> pts;
  pts.reserve(n);
  for (int i = 0; i < n; ++i) pts.emplace_back(P.row(i).data(), P.row(i).data() + 4);
  // The points in coordinate order: to refuse duplicates and to find each vertex's index after the
  // (spatially sorted) insertion.
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i) order[i] = i;
  auto row = [&](int i) { return Coords{P(i, 0), P(i, 1), P(i, 2), P(i, 3)}; };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return row(a) < row(b); });
  for (int k = 1; k < n; ++k)
    if (row(order[k]) == row(order[k - 1]))
      throw Error("4D Delaunay: points " + std::to_string(order[k - 1]) + " and " + std::to_string(order[k]) +
                  " coincide");
  DT4 dt(4);
  dt.insert(pts.begin(), pts.end());
  if (dt.current_dimension() != 4) throw Error("4D Delaunay: the points do not span 4 dimensions");
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
    const Coords c = coords_of(v->point());
    const auto it = std::lower_bound(order.begin(), order.end(), c, [&](int i, const Coords& x) { return row(i) < x; });
    v->data() = *it;
  }
  int count = 0;
  for (auto c = dt.finite_full_cells_begin(); c != dt.finite_full_cells_end(); ++c) c->data() = count++;
  for (auto c = dt.full_cells_begin(); c != dt.full_cells_end(); ++c)
    if (dt.is_infinite(c)) c->data() = -1;
  Delaunay4 out;
  out.simplices.resize(count, 5);
  out.neighbors.resize(count, 5);
  for (auto c = dt.finite_full_cells_begin(); c != dt.finite_full_cells_end(); ++c) {
    const int id = c->data();
    for (int i = 0; i < 5; ++i) {
      out.simplices(id, i) = c->vertex(i)->data();
      out.neighbors(id, i) = c->neighbor(i)->data();
    }
  }
  return out;
}

int orientation_4d(const Eigen::Matrix<double, 5, 4, Eigen::RowMajor>& P) {
  std::vector<K4::Point_d> pts;
  for (int i = 0; i < 5; ++i) pts.emplace_back(P.row(i).data(), P.row(i).data() + 4);
  const CGAL::Orientation o = K4().orientation_d_object()(pts.begin(), pts.end());
  return o == CGAL::POSITIVE ? 1 : o == CGAL::NEGATIVE ? -1 : 0;
}

}  // namespace dfm
