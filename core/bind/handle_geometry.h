#pragma once
// Handle geometry for meshing and the boundary conditions it implies (handle order of core/rig/rig.h:
// points, bones, cage vertices, regions).
#include <array>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Sparse>

#include "core/rig/rig.h"

namespace dfm {

// A position that must be a tet vertex, with the weights it imposes there.
struct HandleSample {
  Eigen::Vector3d x;
  std::vector<std::pair<int, double>> w;  // (handle, weight); weights sum to one
  int handle = -1;                        // the handle it stands for (error messages)
  bool required = true;                   // points and cage vertices must lie in the volume; bone samples may not
};

double mean_edge_length(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// Point handles, bone samples (both joints included, about `spacing` apart) and cage vertices.
// A joint shared by k bones yields k coincident samples; BoundaryRows averages them to 1/k each.
std::vector<HandleSample> sample_handles(const Rig& rig, double spacing);

// Every cage stacked: vertices in handle order, facets and extra edges indexing them.
struct CageSoup {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F, E;
  std::vector<int> handle;  // handle index of each stacked vertex
  std::vector<int> cage;    // which cage each facet belongs to
};
CageSoup stack_cages(const Rig& rig);
// A cage is closed when every edge has exactly two facets.
bool is_closed_surface(const Eigen::MatrixXi& F);

// Accumulates constraints per tet vertex; coinciding constraints are averaged.
class BoundaryRows {
 public:
  void add(int vertex, const std::vector<std::pair<int, double>>& w);
  bool has(int vertex) const;
  // b (sorted) and bc (#b x num_handles, rows normalized to sum to one).
  void finish(int num_handles, Eigen::VectorXi& b, Eigen::MatrixXd& bc) const;

 private:
  std::vector<std::pair<int, std::vector<std::pair<int, double>>>> rows_;
  std::vector<int> index_;  // vertex -> row or -1
};

// Tet vertices lying on a cage facet (or extra edge) within tol get the barycentric coordinates of
// that facet's (edge's) cage-vertex handles; vertices already constrained are left alone.
void add_cage_surface_rows(const Eigen::MatrixXd& TV, const CageSoup& cages, double tol, BoundaryRows& rows);

// Merges points closer than tol (uniform hash grid); returns the index of each added point.
class PointWelder {
 public:
  explicit PointWelder(double tol) : tol_(tol) {}
  int insert(const Eigen::Vector3d& x);  // always a new point (the surface's own vertices)
  int add(const Eigen::Vector3d& x);     // existing index if one is within tol, else a new one
  int find(const Eigen::Vector3d& x) const;  // -1 if none within tol
  const std::vector<Eigen::Vector3d>& points() const { return pts_; }
  Eigen::MatrixXd matrix() const;

 private:
  std::array<long long, 3> cell(const Eigen::Vector3d& x) const;
  static long long hash(const std::array<long long, 3>& c);
  double tol_;
  std::vector<Eigen::Vector3d> pts_;
  std::unordered_multimap<long long, int> grid_;
};

}  // namespace dfm
