// Graph-cut segmentation of winding-number volumes (Jacobson 2013, section 8.5.1, Eqs. 8.7-8.10):
// the cut is a true minimum of the energy (brute force on small graphs), the shared-face adjacency,
// and, on messy copies of a closed surface with a thin part and one with a tunnel, the cut classifies
// tets better than the 0.5 threshold against the exact inside of the closed reference (voxels).
#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "core/bind/bind_volume.h"
#include "core/bind/fem.h"
#include "core/bind/graph_cut_segmentation.h"
#include "core/bind/robust_volume.h"
#include "core/bind/tet_face_adjacency.h"
#include "core/bind/tetrahedralize.h"
#include "core/bind/winding_bvh.h"
#include "core/mesh/mesh_info.h"
#include "core/util/error.h"
#include "tests/volume_test_meshes.h"
#include "tests/voxel_test_meshes.h"

using namespace dfm;
using dfm::test::TaggedFace;
using dfm::test::VoxelShape;

namespace {

// Eq. 8.8 with Eqs. 8.9 and 8.10, written out directly.
double median_of(Eigen::VectorXd x) {
  std::sort(x.data(), x.data() + x.size());
  return x(x.size() / 2);
}

// vol empty: every tet weighs 1; else volume / median volume. Areas are divided by their median.
double energy(const std::vector<char>& x, const Eigen::VectorXd& w, const Eigen::VectorXd& vol,
              const Eigen::MatrixXi& pairs, const Eigen::VectorXd& area, const std::vector<char>& on,
              const GraphCutOptions& o) {
  double e = 0;
  for (int i = 0; i < w.size(); ++i)
    e += (vol.size() ? vol(i) / median_of(vol) : 1.0) * (x[i] ? std::max(1 - w(i), 0.0) : std::max(w(i), 0.0));
  for (int a = 0; a < pairs.rows(); ++a) {
    if (x[pairs(a, 0)] == x[pairs(a, 1)]) continue;
    const double dw = w(pairs(a, 0)) - w(pairs(a, 1));
    e += o.gamma * area(a) / median_of(area) * std::exp(-dw * dw / (2 * o.sigma * o.sigma)) * (on[a] ? o.surface_factor : 1.0);
  }
  return e;
}

}  // namespace

TEST_CASE("graph cut: the labels minimize Eq. 8.8 (brute force over every labelling)", "[graphcut]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(0, 1);
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 11, m = 24;
    Eigen::VectorXd w(n), vol;
    for (int i = 0; i < n; ++i) w(i) = -0.3 + 1.6 * U(rng);
    if (trial % 2) {
      vol.resize(n);
      for (int i = 0; i < n; ++i) vol(i) = 0.01 + U(rng);
    }
    Eigen::MatrixXi pairs(m, 2);
    Eigen::VectorXd area(m);
    std::vector<char> on(m);
    for (int a = 0; a < m; ++a) {
      pairs(a, 0) = static_cast<int>(U(rng) * n) % n;
      pairs(a, 1) = (pairs(a, 0) + 1 + static_cast<int>(U(rng) * (n - 1)) % (n - 1)) % n;
      area(a) = 0.1 + U(rng);
      on[a] = U(rng) < 0.3;
    }
    GraphCutOptions o;
    o.gamma = 0.2 + 2 * U(rng);
    o.sigma = 0.1 + 0.5 * U(rng);
    o.surface_factor = U(rng);
    const std::vector<char> cut = graph_cut_segmentation(w, vol, pairs, area, on, o);
    double best = 1e300;
    for (int bits = 0; bits < (1 << n); ++bits) {
      std::vector<char> x(n);
      for (int i = 0; i < n; ++i) x[i] = (bits >> i) & 1;
      best = std::min(best, energy(x, w, vol, pairs, area, on, o));
    }
    INFO("trial " << trial);
    REQUIRE(energy(cut, w, vol, pairs, area, on, o) <= best + 1e-9);
  }
}

TEST_CASE("graph cut: gamma 0 is the threshold; bad input is refused", "[graphcut]") {
  Eigen::VectorXd w(4);
  w << 0.2, 0.7, 0.51, -1.0;
  Eigen::MatrixXi pairs(2, 2);
  pairs << 0, 1, 1, 2;
  Eigen::VectorXd area = Eigen::VectorXd::Ones(2);
  GraphCutOptions o;
  o.gamma = 0;
  REQUIRE(graph_cut_segmentation(w, Eigen::VectorXd(), pairs, area, {}, o) == std::vector<char>{0, 1, 1, 0});
  REQUIRE(threshold_segmentation(w) == std::vector<char>{0, 1, 1, 0});
  // With a huge gamma the coupled chain 0-1-2 takes one label, the one with the smaller total data
  // cost (inside costs sum(1 - w), outside sum(w)); tet 3 is uncoupled.
  o.gamma = 1e6;
  const std::vector<char> x = graph_cut_segmentation(w, Eigen::VectorXd(), pairs, area, {}, o);
  REQUIRE(x[0] == x[1]);
  REQUIRE(x[1] == x[2]);
  REQUIRE(x[0] == ((0.2 + 0.7 + 0.51) > 1.5 ? 1 : 0));
  REQUIRE(x[3] == 0);
  pairs(1, 1) = 4;
  REQUIRE_THROWS_AS(graph_cut_segmentation(w, Eigen::VectorXd(), pairs, area, {}, o), Error);
  pairs(1, 1) = 2;
  REQUIRE_THROWS_AS(graph_cut_segmentation(w, Eigen::VectorXd(), pairs, Eigen::VectorXd::Ones(3), {}, o), Error);
  REQUIRE_THROWS_AS(graph_cut_segmentation(w, Eigen::VectorXd(), pairs, area, {1}, o), Error);
  REQUIRE_THROWS_AS(graph_cut_segmentation(w, Eigen::VectorXd::Ones(3), pairs, area, {}, o), Error);
  REQUIRE_THROWS_AS(graph_cut_segmentation(w, -Eigen::VectorXd::Ones(4), pairs, area, {}, o), Error);
}

TEST_CASE("tet face adjacency: shared faces, their areas and surface flags", "[graphcut]") {
  // Three tets in a fan around the z axis edge (0,1), consecutive ones sharing a face.
  TetMesh m;
  m.V.resize(5, 3);
  m.V << 0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 1, 0, -1, 0, 0;
  m.T.resize(3, 4);
  m.T << 0, 2, 3, 1, 0, 3, 4, 1, 0, 1, 2, 4;  // the last shares (0,1,2) with the first, (0,1,4) with the second
  const TetFaceAdjacency adj = tet_face_adjacency(m);
  REQUIRE(adj.tets.rows() == 3);
  for (int s = 0; s < 3; ++s) {
    REQUIRE(adj.tets(s, 0) < adj.tets(s, 1));
    REQUIRE(adj.faces(s, 0) == 0);
    REQUIRE(adj.faces(s, 1) == 1);
    REQUIRE(adj.area(s) == Approx(0.5));  // right triangles with legs 1 and 1 in a coordinate plane
  }
  Eigen::MatrixXi F(2, 3);
  F << 3, 1, 0, 7, -1, 2;  // (0,1,3) in another order; a row with a dropped vertex
  const std::vector<char> on = shared_faces_on_surface(adj, F);
  for (int s = 0; s < 3; ++s) REQUIRE(on[s] == (adj.faces(s, 2) == 3));
}

namespace {

// Segmentation input the way the robust volume makes it (core/bind/bind_volume.cpp): TetGen on the
// surface's points in a padded box, winding numbers at centroids, shared faces and input facets.
struct Problem {
  TetMesh tets;
  Eigen::VectorXd w;
  Eigen::VectorXd volume;
  TetFaceAdjacency adj;
  std::vector<char> on;
};

Problem make_problem(const TriMesh& messy) {
  Plc plc;
  const Eigen::RowVector3d lo = messy.V.colwise().minCoeff().array() - 1, hi = messy.V.colwise().maxCoeff().array() + 1;
  plc.V.resize(messy.V.rows() + 8, 3);
  plc.V.topRows(messy.V.rows()) = messy.V;
  const int o = static_cast<int>(messy.V.rows());
  for (int c = 0; c < 8; ++c)
    for (int k = 0; k < 3; ++k) plc.V(o + c, k) = ((c >> k) & 1) ? hi(k) : lo(k);
  static const int box[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  plc.F.resize(12, 3);
  for (int f = 0; f < 12; ++f)
    for (int k = 0; k < 3; ++k) plc.F(f, k) = o + box[f][k];
  const TetgenResult r = tetrahedralize(plc, "pq1.414Y");
  Problem p;
  p.tets = r.mesh;
  p.w = winding_numbers(build_winding_tree(messy.V, messy.F), tet_centroids(p.tets));
  p.volume = tet_volumes(p.tets.V, p.tets.T);
  p.adj = tet_face_adjacency(p.tets);
  Eigen::MatrixXi F = messy.F;
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) F(f, k) = r.input_to_tet(F(f, k));
  p.on = shared_faces_on_surface(p.adj, F);
  return p;
}

struct Score {
  int tets = 0;
  double volume = 0;
};

// Tets whose label disagrees with the exact inside of the closed reference at their centroid.
Score misclassified(const Problem& p, const std::vector<char>& in, const VoxelShape& shape) {
  Score s;
  for (int t = 0; t < p.tets.T.rows(); ++t) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) c += 0.25 * p.tets.V.row(p.tets.T(t, k)).transpose();
    if (static_cast<bool>(in[t]) == shape.contains(c)) continue;
    const Eigen::Vector3d a = p.tets.V.row(p.tets.T(t, 0)), b = p.tets.V.row(p.tets.T(t, 1)),
                          d = p.tets.V.row(p.tets.T(t, 2)), e = p.tets.V.row(p.tets.T(t, 3));
    ++s.tets;
    s.volume += std::abs((b - a).cross(d - a).dot(e - a)) / 6;  // independent of fem.h's tet_volumes
  }
  return s;
}

void compare(const char* name, const VoxelShape& shape, const TriMesh& closed, const TriMesh& messy) {
  // The reference is a closed, outward surface enclosing exactly the voxels.
  REQUIRE(is_closed(closed.F));
  REQUIRE(signed_volume(closed.V, closed.F) == Approx(static_cast<double>(shape.voxels.size())));
  REQUIRE(boundary_edge_count(messy.F) > 0);
  const Problem p = make_problem(messy);
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<char> cut = graph_cut_segmentation(p.w, p.volume, p.adj.tets, p.adj.area, p.on);
  const double cut_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const Score sc = misclassified(p, cut, shape), st = misclassified(p, threshold_segmentation(p.w), shape);
  // For scale: the closed reference's own winding number, thresholded (tets straddling the surface).
  Problem clean = p;
  clean.w = winding_numbers(build_winding_tree(closed.V, closed.F), tet_centroids(p.tets));
  const Score s0 = misclassified(clean, threshold_segmentation(clean.w), shape);
  std::printf("%s: %d tets; misclassified: threshold %d tets / volume %.3f, cut %d tets / volume %.3f (%.3f s); "
              "closed reference thresholded: %d / %.3f\n",
              name, static_cast<int>(p.tets.T.rows()), st.tets, st.volume, sc.tets, sc.volume, cut_s, s0.tets, s0.volume);
  CHECK(st.tets > 0);  // the messy input does fool the threshold
  CHECK(sc.tets < st.tets);
  CHECK(sc.volume < st.volume);
}

}  // namespace

namespace {

// A 4^3 body with a fin one voxel thick (section 8.6: thin parts), and its messy copy: a hole in the
// fin's top, a flipped patch underneath, duplicated triangles on the body.
struct FinShape {
  VoxelShape shape;
  TriMesh closed, messy;
};
FinShape fin_shape() {
  FinShape s;
  s.shape.add_box({0, 0, 0}, {4, 4, 4});
  s.shape.add_box({4, 0, 2}, {10, 4, 3});
  std::vector<TaggedFace> tags;
  s.closed = dfm::test::voxel_surface(s.shape, 2, &tags);
  auto on_fin = [](const TaggedFace& f, int side, int x0, int x1, int y0, int y1) {
    return f.side == side && f.voxel[0] >= x0 && f.voxel[0] < x1 && f.voxel[1] >= y0 && f.voxel[1] < y1 && f.voxel[2] == 2;
  };
  s.messy = dfm::test::mess_up(
      s.closed, tags, [&](const TaggedFace& f) { return on_fin(f, 5, 6, 8, 1, 3); },
      [&](const TaggedFace& f) { return on_fin(f, 4, 4, 6, 0, 2); },
      [&](const TaggedFace& f) { return f.side == 1 && f.voxel[0] == 3 && f.voxel[2] == 0; });
  return s;
}

}  // namespace

TEST_CASE("graph cut beats the threshold on a messy surface with a thin part", "[graphcut][volume]") {
  const FinShape s = fin_shape();
  compare("thin part", s.shape, s.closed, s.messy);
}

TEST_CASE("graph cut beats the threshold on a messy surface with a tunnel", "[graphcut][volume]") {
  // An 8 x 8 x 3 block with a 2 x 2 tunnel through it (genus 1).
  VoxelShape shape;
  shape.add_box({0, 0, 0}, {8, 8, 3});
  shape.remove_box({3, 3, 0}, {5, 5, 3});
  std::vector<TaggedFace> tags;
  const TriMesh closed = dfm::test::voxel_surface(shape, 2, &tags);
  const TriMesh messy = dfm::test::mess_up(
      closed, tags,
      [](const TaggedFace& f) { return f.side == 1 && f.voxel[0] == 2 && f.voxel[1] == 3 && f.voxel[2] < 2; },  // tunnel wall hole
      [](const TaggedFace& f) { return f.side == 5 && f.voxel[0] < 2 && f.voxel[1] < 3; },  // flipped top patch
      [](const TaggedFace& f) { return f.side == 2 && f.voxel[0] >= 5; });                   // duplicated side
  compare("tunnel", shape, closed, messy);
}

TEST_CASE("the robust bind volume segments by graph cut unless told to threshold", "[graphcut][volume]") {
  const FinShape s = fin_shape();
  Rig rig;
  rig.points.push_back({Eigen::Vector3d(2, 2, 2), "body"});
  rig.points.push_back({Eigen::Vector3d(9, 2, 2.5), "fin tip"});
  double error[2];
  for (auto seg : {VolumeOptions::Segmentation::Cut, VolumeOptions::Segmentation::Threshold}) {
    VolumeOptions opts;
    opts.segmentation = seg;
    const BindVolume v = build_bind_volume(s.messy, rig, opts);
    std::string notes;
    for (const std::string& n : v.notes) notes += n + "\n";
    INFO(notes);
    const bool cut = seg == VolumeOptions::Segmentation::Cut;
    REQUIRE(notes.find(cut ? "by graph cut" : "with winding number > 0.5") != std::string::npos);
    // No self-intersections once the duplicated triangles are dropped: TetGen accepts the facets (8.5).
    REQUIRE(notes.find("the surface's facets are constrained") != std::string::npos);
    error[cut ? 0 : 1] = std::abs(tet_volumes(v.tets.V, v.tets.T).sum() - static_cast<double>(s.shape.voxels.size()));
  }
  std::printf("bind volume: |volume - exact| cut %.3f, threshold %.3f\n", error[0], error[1]);
  CHECK(error[0] < error[1]);
}

TEST_CASE("robust volume: self-intersecting facets fall back to the points alone", "[graphcut][volume]") {
  // Two overlapping closed spheres as one soup: their facets intersect, TetGen refuses them as constraints.
  const TriMesh a = dfm::test::icosphere({0, 0, 0}, 1, 2), b = dfm::test::icosphere({1, 0, 0}, 1, 2);
  const TriMesh both = dfm::test::concat(a, b);
  Rig rig;
  rig.points.push_back({Eigen::Vector3d(-0.5, 0, 0), "a"});
  rig.points.push_back({Eigen::Vector3d(1.5, 0, 0), "b"});
  VolumeOptions opts;
  opts.robust = VolumeOptions::Robust::Always;
  const BindVolume v = build_bind_volume(both, rig, opts);
  std::string notes;
  for (const std::string& n : v.notes) notes += n + "\n";
  INFO(notes);
  REQUIRE(notes.find("TetGen refused the surface's facets") != std::string::npos);
  // The union (winding number 2 in the overlap is inside): two balls minus the lens pi (4r + d)(2r - d)^2 / 12,
  // scaled by how much of the ball the icosphere encloses.
  const double ball = 4 * M_PI / 3, lens = M_PI * 5 / 12;
  const double union_volume = (2 * ball - lens) * dfm::test::enclosed_volume(a.V, a.F) / ball;
  REQUIRE(tet_volumes(v.tets.V, v.tets.T).sum() == Approx(union_volume).epsilon(0.03));
}
