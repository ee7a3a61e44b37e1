// Does edit_refined (Southern 2008, 4.5.1; issue 35) converge? The spike of test_manifold_refine (a still
// unit sphere keyed at t = 0..4, the pole pulled 1.2 out at t = 2, region radius 0.6 over [1, 3]) edited
// on a coarse sphere, unrefined and refined, and the same edit on a sphere subdivided finer from the start
// (the reference, its frames). A slice's neighbour-angle percentile ("own") depends on its resolution
// where it crosses a crease, so the first judge is the distance to the reference's slice at the same t: both ways, brute-force closest
// points, as a fraction of the reference slice's bounding diagonal (max and 99th percentile), and the
// angle between each slice vertex's normal and the normal of the closest reference triangle (90th, 99th
// percentile, both ways). Also: the slice's top (the handle is dragged to y = 2.2 at t = 2), its longest
// edge and the 1st percentile of its triangles' smallest corners.
// Arguments: [weights: equal|reciprocal|primal-boundary|dual|all, default all] [coarse levels, default 34]
// [reference level, default 5] [times, default 1.5,2,2.5] [rounds, default
// RefineOptions'] [spin: the sphere turns this many degrees a unit of time about y, default 0]
// [layers a unit of time, default 1]. Rows "frame": the editor's frames
// (manifold_frame.h, a prism slab's layers interpolated), the other rows per-tetrahedron slices.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "core/anim/manifold.h"
#include "core/anim/manifold_refine.h"
#include "core/anim/slice.h"
#include "core/anim/manifold_frame.h"
#include "tests/transition_test_meshes.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;

namespace {

// A unit sphere over t = 0..4, `per_unit` layers a unit of time, turning `spin` degrees a unit of time
// about y (the pole stays put; the layers' time edges shear along the surface).
AnimationManifold sphere_manifold(int levels, double spin, int per_unit) {
  const TriMesh s = dfm::test::icosphere(Eigen::Vector3d::Zero(), 1.0, levels);
  std::vector<Eigen::MatrixXd> layers;
  std::vector<double> times;
  for (int i = 0; i <= 4 * per_unit; ++i) {
    const double t = static_cast<double>(i) / per_unit;
    layers.push_back(s.V * Eigen::AngleAxisd(spin * t * M_PI / 180, Eigen::Vector3d::UnitY()).toRotationMatrix().transpose());
    times.push_back(t);
  }
  return build_manifold(layers, s.F, times);
}

std::vector<Eigen::Vector3d> face_normals(const TriMesh& m) {
  std::vector<Eigen::Vector3d> N(static_cast<size_t>(m.F.rows()));
  for (int f = 0; f < m.F.rows(); ++f) {
    const Eigen::Vector3d p = m.V.row(m.F(f, 0)), q = m.V.row(m.F(f, 1)), r = m.V.row(m.F(f, 2));
    N[f] = (q - p).cross(r - p).normalized();
  }
  return N;
}

double percentile(std::vector<double> v, int p) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, v.size() * p / 100)];
}

// From a's vertices to b, every triangle tried: the distance, and the angle (degrees) between a's
// area-weighted vertex normal and the normal of b's closest triangle.
void one_way(const TriMesh& a, const TriMesh& b, std::vector<double>& dist, std::vector<double>& angle) {
  const std::vector<Eigen::Vector3d> Nb = face_normals(b);
  Eigen::MatrixXd VN = Eigen::MatrixXd::Zero(a.V.rows(), 3);
  for (int f = 0; f < a.F.rows(); ++f) {
    const Eigen::Vector3d p = a.V.row(a.F(f, 0)), q = a.V.row(a.F(f, 1)), r = a.V.row(a.F(f, 2));
    for (int j = 0; j < 3; ++j) VN.row(a.F(f, j)) += (q - p).cross(r - p).transpose();
  }
  for (int i = 0; i < a.V.rows(); ++i) {
    const Eigen::Vector3d p = a.V.row(i);
    double best = 1e300;
    int bf = 0;
    for (int f = 0; f < b.F.rows(); ++f) {
      const double d = dfm::test::point_triangle_distance(p, b.V.row(b.F(f, 0)).transpose(), b.V.row(b.F(f, 1)).transpose(),
                                                          b.V.row(b.F(f, 2)).transpose());
      if (d < best) best = d, bf = f;
    }
    dist.push_back(best);
    angle.push_back(std::acos(std::clamp(Eigen::Vector3d(VN.row(i).normalized()).dot(Nb[bf]), -1.0, 1.0)) * 180 / M_PI);
  }
}

struct Row {
  double top, dist_max, dist_p99, angle_p90, angle_p99, longest, corner_p1, own_p90, own_p99;
  int triangles;
};

Row measure(const TriMesh& a, const TriMesh& ref) {
  std::vector<double> dist, angle;
  one_way(a, ref, dist, angle);
  one_way(ref, a, dist, angle);
  const double diag = (ref.V.colwise().maxCoeff() - ref.V.colwise().minCoeff()).norm();
  Row r{};
  r.top = a.V.col(1).maxCoeff();
  r.dist_max = *std::max_element(dist.begin(), dist.end()) / diag;
  r.dist_p99 = percentile(dist, 99) / diag;
  r.angle_p90 = percentile(angle, 90);
  r.angle_p99 = percentile(angle, 99);
  std::vector<double> corners;
  for (int f = 0; f < a.F.rows(); ++f) {
    double smallest = 180;
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d p = a.V.row(a.F(f, j)), u = Eigen::Vector3d(a.V.row(a.F(f, (j + 1) % 3))) - p,
                            w = Eigen::Vector3d(a.V.row(a.F(f, (j + 2) % 3))) - p;
      r.longest = std::max(r.longest, u.norm());
      smallest = std::min(smallest, std::atan2(u.cross(w).norm(), u.dot(w)) * 180 / M_PI);
    }
    corners.push_back(smallest);
  }
  r.corner_p1 = percentile(corners, 1);
  {
    const std::vector<Eigen::Vector3d> N = face_normals(a);
    std::map<std::pair<int, int>, int> edge_face;
    std::vector<double> own;
    for (int f = 0; f < a.F.rows(); ++f)
      for (int j = 0; j < 3; ++j) {
        const int u = a.F(f, j), w = a.F(f, (j + 1) % 3);
        auto it = edge_face.find({w, u});
        if (it == edge_face.end()) edge_face[{u, w}] = f;
        else own.push_back(std::acos(std::clamp(N[f].dot(N[it->second]), -1.0, 1.0)) * 180 / M_PI);
      }
    r.own_p90 = percentile(own, 90);
    r.own_p99 = percentile(own, 99);
  }
  r.triangles = static_cast<int>(a.F.rows());
  return r;
}

double longest_edge(const TriMesh& m) {
  double l = 0;
  for (int f = 0; f < m.F.rows(); ++f)
    for (int j = 0; j < 3; ++j) l = std::max(l, (m.V.row(m.F(f, j)) - m.V.row(m.F(f, (j + 1) % 3))).norm());
  return l;
}

void print(const char* what, const Row& r) {
  std::printf("    %-9s top %.4f  dist max %.4f p99 %.4f  normal p90 %5.2f p99 %5.2f  longest %.3f  corner p1 %4.1f  %d tris  own p90 %5.2f p99 %5.2f\n", what,
              r.top, r.dist_max, r.dist_p99, r.angle_p90, r.angle_p99, r.longest, r.corner_p1, r.triangles, r.own_p90, r.own_p99);
}


}  // namespace

int main(int argc, char** argv) {
  const std::string wname = argc > 1 ? argv[1] : "all";
  const std::string levels = argc > 2 ? argv[2] : "34";
  const int ref_level = argc > 3 ? std::stoi(argv[3]) : 5;
  std::vector<double> times;
  {
    std::stringstream ss(argc > 4 ? argv[4] : "1.5,2,2.5");
    for (std::string s; std::getline(ss, s, ',');) times.push_back(std::stod(s));
  }
  std::vector<LaplacianWeights> schemes;
  if (wname == "all")
    schemes = {LaplacianWeights::Equal, LaplacianWeights::Reciprocal, LaplacianWeights::PrimalBoundary, LaplacianWeights::Dual};
  else
    schemes = {parse_laplacian_weights(wname)};
  EditRegionSpec region;
  region.center = Eigen::Vector3d(0, 1, 0);
  region.radius = 0.6;
  region.t0 = 1;
  region.t1 = 3;
  EditHandleSpec handle;
  handle.point = Eigen::Vector3d(0, 1, 0);
  handle.time = 2;
  ManifoldDrag drag;
  drag.translation = Eigen::Vector3d(0, 1.2, 0);
  RefineOptions none, refine;
  none.max_rounds = 0;
  if (argc > 5) refine.max_rounds = std::stoi(argv[5]);
  const double spin = argc > 6 ? std::stod(argv[6]) : 0;
  const int per_unit = argc > 7 ? std::stoi(argv[7]) : 1;
  for (LaplacianWeights w : schemes) {
    ManifoldEditOptions options;
    options.weights = w;
    const AnimationManifold fine = edit_refined(sphere_manifold(ref_level, spin, per_unit), region, handle, options, drag, none);
    std::printf("%s weights, reference: level %d sphere (%d vertices a layer)\n", laplacian_weights_name(w), ref_level,
                fine.prism_slabs.front().count);
    for (char c : levels) {
      const int level = c - '0';
      RefineStats ps, rs;
      const AnimationManifold m = sphere_manifold(level, spin, per_unit);
      const AnimationManifold plain = edit_refined(m, region, handle, options, drag, none, &ps);
      const AnimationManifold refined = edit_refined(m, region, handle, options, drag, refine, &rs);
      std::printf("  level %d (%d vertices a layer): %d vertices added in %d rounds, longest region edge %.2f -> %.2f mean lengths\n", level,
                  m.prism_slabs.front().count, rs.added, rs.rounds, ps.longest, rs.longest);
      for (double t : times) {
        const TriMesh r = manifold_frame(fine, t).mesh;
        std::printf("   t = %.2f (reference top %.4f, longest edge %.3f)\n", t, r.V.col(1).maxCoeff(), longest_edge(r));
        print("reference", measure(r, r));
        print("unedited", measure(slice_manifold(m, SliceAxis::T, t).mesh, r));
        print("unrefined", measure(slice_manifold(plain, SliceAxis::T, t).mesh, r));
        print("refined", measure(slice_manifold(refined, SliceAxis::T, t).mesh, r));
        print("frame un", measure(manifold_frame(plain, t).mesh, r));
        print("frame ref", measure(manifold_frame(refined, t).mesh, r));
        std::fflush(stdout);
      }
    }
  }
}
