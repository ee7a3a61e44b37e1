// How transition in-betweens look (issue 30): for each pair of keys, the keys and the slices at
// t = 0.25, 0.5, 0.75 measured the same way: triangles, the angle between edge-neighbouring
// triangles' normals (median, 90th, 99th percentile), the share of triangles with a corner under 1,
// 5 and 10 degrees; then the Euler characteristic over t = 0, 0.05, ..., 1 and the build's stages;
// then the documented field's own zero set on a grid (Euler characteristic over u, and the same
// measures at u = 0.25, 0.5, 0.75), which tells the field's roughness from the sampling's.
// Arguments: [all|bunny|torus|spheres|teddy] [layers] [spacing] [grid spacing in lattice spacings,
// default 0.5] [relax rounds (TransitionOptions::relax_rounds; 0 for the unsmoothed level set)]
// [close look: the Euler characteristic of the slices and of the field every 1/192 from there; -1 for
// none] [TransitionOptions::transient_life; 0 keeps the lattice's short-lived topology]
// [TransitionOptions::crease_rounding; 0 blends the signed distances themselves].
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>


#include "core/anim/key_alignment.h"
#include "core/anim/key_distance.h"
#include "core/anim/rounded_distance.h"
#include "core/anim/manifold.h"
#include "core/anim/slice.h"
#include "core/anim/slice_table.h"
#include "core/anim/transition.h"
#include "core/bind/handle_geometry.h"
#include "core/mesh/io.h"
#include "tests/transition_test_meshes.h"

using namespace dfm;

namespace {

struct Quality {
  int triangles = 0;
  double p50 = 0, p90 = 0, p99 = 0;
  double under1 = 0, under5 = 0, under10 = 0;  // shares of triangles with a corner under that angle
};

Quality quality(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  Quality q;
  q.triangles = static_cast<int>(F.rows());
  Eigen::MatrixXd N(F.rows(), 3);
  int n1 = 0, n5 = 0, n10 = 0;
  for (int f = 0; f < F.rows(); ++f) {
    Eigen::Vector3d p[3];
    for (int j = 0; j < 3; ++j) p[j] = V.row(F(f, j)).transpose();
    N.row(f) = (p[1] - p[0]).cross(p[2] - p[0]).normalized().transpose();
    double smallest = 180;
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d a = p[(j + 1) % 3] - p[j], b = p[(j + 2) % 3] - p[j];
      smallest = std::min(smallest, std::atan2(a.cross(b).norm(), a.dot(b)) * 180 / M_PI);
    }
    n1 += smallest < 1, n5 += smallest < 5, n10 += smallest < 10;
  }
  std::map<std::pair<int, int>, int> first;
  std::vector<double> angles;
  for (int f = 0; f < F.rows(); ++f)
    for (int j = 0; j < 3; ++j) {
      const int a = F(f, j), b = F(f, (j + 1) % 3);
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto it = first.find(key);
      if (it == first.end()) {
        first.emplace(key, f);
      } else {
        const double c = std::max(-1.0, std::min(1.0, N.row(f).dot(N.row(it->second))));
        angles.push_back(std::acos(c) * 180 / M_PI);
      }
    }
  std::sort(angles.begin(), angles.end());
  if (!angles.empty()) {
    q.p50 = angles[angles.size() / 2];
    q.p90 = angles[angles.size() * 9 / 10];
    q.p99 = angles[angles.size() * 99 / 100];
  }
  q.under1 = double(n1) / F.rows(), q.under5 = double(n5) / F.rows(), q.under10 = double(n10) / F.rows();
  return q;
}

void print(const char* what, const Quality& q) {
  std::printf("  %-8s %6d triangles, normals %5.1f / %5.1f / %5.1f degrees (median / 90th / 99th), corners under "
              "1, 5, 10 degrees: %4.1f%% %4.1f%% %4.1f%%\n",
              what, q.triangles, q.p50, q.p90, q.p99, 100 * q.under1, 100 * q.under5, 100 * q.under10);
}

TransitionOptions options;
double grid_factor = 0.5;  // the field's grid spacing, in the middle lattice's
double window = -1;        // start of a close look at the Euler characteristic (none when negative)

// t = window, window + 1/192, ... for 18 steps: finer than the layers (1/24 apart by default), so that
// a short topology event of the field shows against the slices' own.
template <class Euler>
void print_window(const Euler& euler) {
  if (window < 0) return;
  std::printf("  close look:");
  for (int i = 0; i < 18; ++i) std::printf(" %.4f:%d", window + i / 192.0, euler(window + i / 192.0));
  std::printf("\n");
}

// The documented field's zero set at u (transition.h: aligned keys, no pairs), by marching tetrahedra
// (six per grid cube, Freudenthal; slice_table.h's cases) on a grid whose signed distances d_s, d_t
// are given: its triangles, and with the grid's points G also its vertices V and the triangles
// oriented toward the positive side (else the orientation is not kept).
Eigen::MatrixXi zero_set_triangles(const Eigen::Array3i& n, const Eigen::VectorXd& d_s, const Eigen::VectorXd& d_t, double u,
                                   const Eigen::MatrixXd* G = nullptr, Eigen::MatrixXd* V = nullptr) {
  const Eigen::VectorXd f = (1 - u) * d_s + u * d_t;
  auto id = [&](int i, int j, int k) { return (i * n[1] + j) * n[2] + k; };
  static const int order[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  std::map<std::pair<int, int>, int> crossing;  // grid edge -> vertex
  auto vertex = [&](int a, int b) {
    const auto key = std::make_pair(std::min(a, b), std::max(a, b));
    return crossing.emplace(key, static_cast<int>(crossing.size())).first->second;
  };
  std::vector<Eigen::RowVector3i> tris;
  for (int i = 0; i + 1 < n[0]; ++i)
    for (int j = 0; j + 1 < n[1]; ++j)
      for (int k = 0; k + 1 < n[2]; ++k)
        for (const auto& o : order) {
          int c[3] = {i, j, k}, corner[4] = {id(i, j, k)}, index = 0;
          for (int s = 0; s < 3; ++s) ++c[o[s]], corner[s + 1] = id(c[0], c[1], c[2]);
          for (int q = 0; q < 4; ++q) index |= (f[corner[q]] >= 0) << q;
          const SliceCase& cs = slice_table()[index];
          for (int t = 0; t < cs.num_triangles; ++t) {
            Eigen::RowVector3i tri;
            for (int e = 0; e < 3; ++e) {
              const auto& edge = kSliceEdges[cs.triangles[t][e]];
              tri[e] = vertex(corner[edge[0]], corner[edge[1]]);
            }
            if (G) {  // normals toward the positive side
              int pos = -1, neg = -1;
              for (int q = 0; q < 4; ++q) (f[corner[q]] >= 0 ? pos : neg) = corner[q];
              auto p = [&](int e) {
                const auto& edge = kSliceEdges[cs.triangles[t][e]];
                const double s = f[corner[edge[0]]] / (f[corner[edge[0]]] - f[corner[edge[1]]]);
                return Eigen::RowVector3d((1 - s) * G->row(corner[edge[0]]) + s * G->row(corner[edge[1]]));
              };
              const Eigen::RowVector3d nrm = (p(1) - p(0)).cross(p(2) - p(0));
              if (nrm.dot(G->row(pos) - G->row(neg)) < 0) std::swap(tri[1], tri[2]);
            }
            tris.push_back(tri);
          }
        }
  Eigen::MatrixXi F(static_cast<Eigen::Index>(tris.size()), 3);
  for (size_t t = 0; t < tris.size(); ++t) F.row(static_cast<Eigen::Index>(t)) = tris[t];
  if (G && V) {
    V->resize(static_cast<Eigen::Index>(crossing.size()), 3);
    for (const auto& [e, v] : crossing) {
      const double s = f[e.first] / (f[e.first] - f[e.second]);
      V->row(v) = (1 - s) * G->row(e.first) + s * G->row(e.second);
    }
  }
  return F;
}

// The documented field's zero set on a grid of grid_factor times the middle lattice's spacing: its
// Euler characteristic over u = 0, 0.05, ..., 1 (where it leaves the keys' range, the spurious
// topology is the field's, not the triangulation's) and its measures at u = 0.25, 0.5, 0.75 (what
// the field looks like sampled that finely).
void print_field_euler(const TriMesh& a, const TriMesh& b) {
  const KeyPlacement p = key_placement(solid_moments(a.V, a.F), solid_moments(b.V, b.F));
  const Eigen::MatrixXd bV = options.align ? to_source_frame(p, b.V) : b.V;
  const double h = grid_factor * options.spacing * std::min(mean_edge_length(a.V, a.F), mean_edge_length(b.V, b.F));
  const Eigen::RowVector3d lo = a.V.colwise().minCoeff().cwiseMin(bV.colwise().minCoeff()).array() - 2 * h;
  const Eigen::RowVector3d hi = a.V.colwise().maxCoeff().cwiseMax(bV.colwise().maxCoeff()).array() + 2 * h;
  const Eigen::Array3i n = ((hi - lo) / h).array().ceil().cast<int>().transpose() + 1;
  Eigen::MatrixXd G(n.prod(), 3);
  for (int i = 0, r = 0; i < n[0]; ++i)
    for (int j = 0; j < n[1]; ++j)
      for (int k = 0; k < n[2]; ++k) G.row(r++) = lo + Eigen::RowVector3d(i, j, k) * h;
  const Eigen::VectorXd d_s = rounded_distance(SignedDistance(a.V, a.F), G, options.crease_rounding);
  const Eigen::VectorXd d_t = rounded_distance(SignedDistance(bV, b.F), G, options.crease_rounding);
  std::printf("  the documented field's zero set, grid %.4g:     ", h);
  for (int i = 0; i <= 20; ++i) std::printf(" %d", dfm::test::euler_characteristic(zero_set_triangles(n, d_s, d_t, i / 20.0)));
  std::printf("\n");
  print_window([&](double u) { return dfm::test::euler_characteristic(zero_set_triangles(n, d_s, d_t, u)); });
  for (double u : {0.25, 0.5, 0.75}) {
    Eigen::MatrixXd V;
    const Eigen::MatrixXi F = zero_set_triangles(n, d_s, d_t, u, &G, &V);
    char what[32];
    std::snprintf(what, sizeof what, "u = %.2f", u);
    print(what, quality(V, F));
  }
}

void run(const char* name, const TriMesh& a, const TriMesh& b) {
  TransitionStats st;
  const AnimationManifold M = build_transition(a, 0, b, 1, options, &st);
  std::printf("%s: %d -> %d vertices, %.2f s (align %.2f, conform %.2f, field %.2f, delaunay %.2f, extract %.2f of which relax %.2f), "
              "%d middle points, %d tets, %d slabs, %d short-lived events merged\n",
              name, static_cast<int>(a.V.rows()), static_cast<int>(b.V.rows()), st.total_seconds, st.align_seconds,
              st.conform_seconds, st.field_seconds, st.delaunay_seconds, st.extract_seconds, st.relax_seconds, st.middle_points, M.num_tets(),
              M.num_slabs(), st.transients);
  print("key 0", quality(a.V, a.F));
  print("key 1", quality(b.V, b.F));
  for (double t : {0.25, 0.5, 0.75}) {
    const ManifoldSlice s = slice_manifold(M, SliceAxis::T, t);
    char what[16];
    std::snprintf(what, sizeof what, "t = %.2f", t);
    print(what, quality(s.mesh.V, s.mesh.F));
  }
  std::printf("  Euler characteristic over t = 0, 0.05, ..., 1:");
  for (int i = 0; i <= 20; ++i)
    std::printf(" %d", dfm::test::euler_characteristic(slice_manifold(M, SliceAxis::T, i / 20.0).mesh.F));
  std::printf("  (keys %d, %d)\n", dfm::test::euler_characteristic(a.F), dfm::test::euler_characteristic(b.F));
  print_window([&](double t) { return dfm::test::euler_characteristic(slice_manifold(M, SliceAxis::T, t).mesh.F); });
  if (options.pairs.rows() == 0) print_field_euler(a, b);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string which = argc > 1 ? argv[1] : "all";
  if (argc > 2) options.layers = std::atoi(argv[2]);
  if (argc > 3) options.spacing = std::atof(argv[3]);
  if (argc > 4) grid_factor = std::atof(argv[4]);
  if (argc > 5) options.relax_rounds = std::atoi(argv[5]);
  if (argc > 6) window = std::atof(argv[6]);
  if (argc > 7) options.transient_life = std::atof(argv[7]);
  if (argc > 8) options.crease_rounding = std::atof(argv[8]);
  const std::string dir = DFM_DATA_DIR;
  if (which == "all" || which == "bunny")
    run("bunny to 3holes", dfm::test::into_unit_box(read_surface(dir + "/bunny.off")),
        dfm::test::into_unit_box(read_surface(dir + "/3holes.off")));
  if (which == "all" || which == "torus")
    run("icosphere 2562 to torus", dfm::test::icosphere(Eigen::Vector3d::Zero(), 0.45, 4),
        dfm::test::torus(Eigen::Vector3d::Zero(), 0.32, 0.12, 100, 50));
  if (which == "all" || which == "spheres")
    run("torus to two spheres", dfm::test::torus(Eigen::Vector3d::Zero(), 0.32, 0.12, 100, 50),
        dfm::test::concat(dfm::test::icosphere(Eigen::Vector3d(-0.22, 0, 0), 0.2, 4),
                          dfm::test::icosphere(Eigen::Vector3d(0.22, 0, 0.01), 0.2, 4)));
  if (which == "all" || which == "teddy")
    run("teddy to key-torus", read_surface(std::string(DFM_SOURCE_DIR) + "/assets/default.obj"),
        read_surface(std::string(DFM_SOURCE_DIR) + "/assets/key-torus.obj"));
  return 0;
}
