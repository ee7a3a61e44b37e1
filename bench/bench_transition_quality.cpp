// How transition in-betweens look (issue 30): for each pair of keys, the keys and the slices at
// t = 0.25, 0.5, 0.75 measured the same way: triangles, the angle between edge-neighbouring
// triangles' normals (median, 90th, 99th percentile), the share of triangles with a corner under 1,
// 5 and 10 degrees; then the Euler characteristic over t = 0, 0.05, ..., 1 and the build's stages.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "core/anim/manifold.h"
#include "core/anim/slice.h"
#include "core/anim/transition.h"
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

void run(const char* name, const TriMesh& a, const TriMesh& b) {
  TransitionStats st;
  const AnimationManifold M = build_transition(a, 0, b, 1, options, &st);
  std::printf("%s: %d -> %d vertices, %.2f s (align %.2f, conform %.2f, field %.2f, delaunay %.2f, extract %.2f), "
              "%d middle points, %d tets, %d slabs\n",
              name, static_cast<int>(a.V.rows()), static_cast<int>(b.V.rows()), st.total_seconds, st.align_seconds,
              st.conform_seconds, st.field_seconds, st.delaunay_seconds, st.extract_seconds, st.middle_points, M.num_tets(),
              M.num_slabs());
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
}

}  // namespace

int main(int argc, char** argv) {
  const std::string which = argc > 1 ? argv[1] : "all";
  if (argc > 2) options.layers = std::atoi(argv[2]);
  if (argc > 3) options.spacing = std::atof(argv[3]);
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
