// Transition build between keys of different topology (Southern 2008, 8.7.1: a 3,000-vertex
// fertility model to a sphere took about 800 s: fill 12.2 s, find 559.5 s, strip 227.1 s).
// Pairs of about 5K vertices each; prints each stage, then the cost of slicing the result next to
// slicing a prism manifold of the same size in tetrahedra (the same CPU slicer). Each pair is built
// without alignment (as before issue 30) and with it (the default: placement, warp, more layers for a
// turn); aligned, also with the plain signed distances and two relax rounds (the field before
// TransitionOptions::crease_rounding) and without refitting the lattice's values
// (TransitionOptions::fit_crossings) or refining the lattice (TransitionOptions::refine_tolerance),
// timed in the same process. Then a box turned a quarter (issue 30): the slice against the rigidly turned box, over 4, 8
// and 12 layers. Then five picked pairs on the teddy and the ring, with and without.
#include <array>
#include <chrono>
#include <map>
#include <cmath>
#include <cstdio>
#include <exception>

#include <Eigen/Geometry>
#include <string>

#include "core/anim/manifold.h"
#include "core/anim/surface_checks.h"
#include "core/anim/slice.h"
#include "core/anim/transition.h"
#include "core/mesh/io.h"
#include "tests/transition_test_meshes.h"

using namespace dfm;
using Clock = std::chrono::steady_clock;

namespace {

double ms_per_slice(const AnimationManifold& M, int n) {
  const auto t = Clock::now();
  size_t tris = 0;
  for (int i = 0; i < n; ++i) tris += slice_manifold(M, SliceAxis::T, M.times.front() + (i + 0.5) / n *
                                                                           (M.times.back() - M.times.front()))
                                          .mesh.F.rows();
  (void)tris;
  return 1e3 * std::chrono::duration<double>(Clock::now() - t).count() / n;
}

void run(const char* name, const TriMesh& a, const TriMesh& b, bool align) {
  TransitionStats st;
  TransitionOptions o;
  o.align = align;
  const AnimationManifold M = build_transition(a, 0, b, 1, o, &st);
  std::printf("%-28s %s: turn %.1f degrees, scale %.3f, align and place %.2f s\n", name, align ? "aligned" : "unaligned",
              st.turn_degrees, st.scale, st.align_seconds);
  std::printf("%-28s %5d -> %5d vertices: total %.2f s (conform and fill %.2f, field %.2f, delaunay %.2f, extract %.2f of which relax %.2f); "
              "%d + %d + %d points, %d 4-simplices, %d Steiner points, %d flips, %d triangles not conforming, %d chords, %d key-plane fixes, %d tets, %d ends tied\n",
              name, static_cast<int>(a.V.rows()), static_cast<int>(b.V.rows()), st.total_seconds, st.conform_seconds,
              st.field_seconds, st.delaunay_seconds, st.extract_seconds, st.relax_seconds, st.source.points, st.middle_points,
              st.target.points, st.simplices, st.source.steiner + st.target.steiner, st.source.flipped + st.target.flipped,
              st.source.missing + st.target.missing, st.source.chords + st.target.chords,
              st.source.plane_fixes + st.target.plane_fixes, st.tets, st.source.tied + st.target.tied);
  if (align) {
    // Baseline in the same process: the field before rounded distances (plain signed distances,
    // two relax rounds).
    TransitionStats plain;
    TransitionOptions p = o;
    p.crease_rounding = 0;
    p.relax_rounds = 2;
    build_transition(a, 0, b, 1, p, &plain);
    std::printf("%-28s plain distances, two relax rounds: total %.2f s (field %.2f, relax %.2f), %d points in the middle; "
                "rounded / plain %.2f\n",
                "", plain.total_seconds, plain.field_seconds, plain.relax_seconds, plain.middle_points,
                st.total_seconds / plain.total_seconds);
    // And without refitting the lattice's values to the field's crossings (crossing_fit.h).
    TransitionStats unfitted;
    TransitionOptions q = o;
    q.fit_crossings = false;
    build_transition(a, 0, b, 1, q, &unfitted);
    std::printf("%-28s values not refitted: total %.2f s (field %.2f); fitted / not %.2f\n", "", unfitted.total_seconds,
                unfitted.field_seconds, st.total_seconds / unfitted.total_seconds);
    // And one lattice spacing everywhere (lattice_refinement.h).
    TransitionStats unrefined;
    TransitionOptions r = o;
    r.refine_tolerance = 0;
    const AnimationManifold U = build_transition(a, 0, b, 1, r, &unrefined);
    std::printf("%-28s lattice not refined: total %.2f s (field %.2f, extract %.2f), %d middle points, %d tets; refined "
                "(%d points added) / not %.2f, slice at t = 0.5 %d / %d triangles\n",
                "", unrefined.total_seconds, unrefined.field_seconds, unrefined.extract_seconds, unrefined.middle_points,
                unrefined.tets, st.refined_points, st.total_seconds / unrefined.total_seconds,
                static_cast<int>(slice_manifold(M, SliceAxis::T, 0.5).mesh.F.rows()),
                static_cast<int>(slice_manifold(U, SliceAxis::T, 0.5).mesh.F.rows()));
  }
  // Baseline in the same process: a prism manifold of the first key over enough layers to hold about
  // as many tetrahedra, sliced by the same slicer.
  const int layers = std::max(2, static_cast<int>(std::lround(st.tets / (3.0 * a.F.rows()))) + 1);
  std::vector<Eigen::MatrixXd> L(layers, a.V);
  std::vector<double> times(layers);
  for (int i = 0; i < layers; ++i) times[i] = static_cast<double>(i) / (layers - 1);
  const AnimationManifold P = build_manifold(L, a.F, times);
  const double mt = ms_per_slice(M, 20), mp = ms_per_slice(P, 20);
  std::printf("%-28s slice %.2f ms (transition, %d tets in its slab) vs %.2f ms (prism baseline, %d tets in %d "
              "slabs): ratio %.2f\n",
              "", mt, M.num_tets(), mp, P.num_tets(), P.num_slabs(), mt / mp);
}

// The box [-2, 2] x [-0.5, 0.5]^2 in quads of `q`, the target turned 90 degrees about z, moved and
// in quads of 4q/3 with the other diagonals; at each t the slice's farthest vertex from the rigidly
// turned box (analytic distance) and its volume (the box's: 4).
TriMesh quad_box(double q, bool other) {
  const int nx = static_cast<int>(std::lround(4 / q)), ny = static_cast<int>(std::lround(1 / q));
  std::map<std::array<int, 3>, int> id;
  TriMesh m;
  std::vector<Eigen::RowVector3d> V;
  std::vector<Eigen::RowVector3i> F;
  const Eigen::Vector3i n(nx, ny, ny);
  const Eigen::Vector3d lo(-2, -0.5, -0.5), hi(2, 0.5, 0.5);
  auto vert = [&](std::array<int, 3> g) {
    auto [it, fresh] = id.emplace(g, static_cast<int>(V.size()));
    if (fresh) V.push_back(Eigen::RowVector3d(lo[0] + (hi[0] - lo[0]) * g[0] / n[0], lo[1] + (hi[1] - lo[1]) * g[1] / n[1],
                                              lo[2] + (hi[2] - lo[2]) * g[2] / n[2]));
    return it->second;
  };
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      for (int p = 0; p < n[b]; ++p)
        for (int r = 0; r < n[c]; ++r) {
          auto at = [&](int dp, int dr) {
            std::array<int, 3> g;
            g[a] = side * n[a], g[b] = p + dp, g[c] = r + dr;
            return vert(g);
          };
          int v00 = at(0, 0), v10 = at(1, 0), v11 = at(1, 1), v01 = at(0, 1);
          if (side == 0) std::swap(v10, v01);
          if (!other) F.push_back({v00, v10, v11}), F.push_back({v00, v11, v01});
          else F.push_back({v00, v10, v01}), F.push_back({v10, v11, v01});
        }
    }
  m.V.resize(static_cast<Eigen::Index>(V.size()), 3);
  for (size_t i = 0; i < V.size(); ++i) m.V.row(static_cast<Eigen::Index>(i)) = V[i];
  m.F.resize(static_cast<Eigen::Index>(F.size()), 3);
  for (size_t i = 0; i < F.size(); ++i) m.F.row(static_cast<Eigen::Index>(i)) = F[i];
  return m;
}

void turn(double q, double turn_degrees, double max_turn) {
  const TriMesh a = quad_box(q, false);
  TriMesh b = quad_box(4 * q / 3, true);
  const Eigen::Vector3d shift(1.5, 2, 0.5);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(turn_degrees * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  b.V = ((b.V * R.transpose()).rowwise() + shift.transpose()).eval();
  TransitionOptions o;
  o.max_turn_per_layer = max_turn;
  TransitionStats st;
  const AnimationManifold M = build_transition(a, 0, b, 1, o, &st);
  std::printf("box turned %.0f, quads %.3f, max turn %.1f per layer: %d -> %d vertices, %.2f s (align and place %.3f, "
              "delaunay %.2f), %d tets\n", turn_degrees, q, max_turn, static_cast<int>(a.V.rows()),
              static_cast<int>(b.V.rows()), st.total_seconds, st.align_seconds, st.delaunay_seconds, st.tets);
  for (double t : {0.1, 0.25, 0.5, 0.75, 0.9}) {
    const ManifoldSlice s = slice_manifold(M, SliceAxis::T, t);
    double best = 1e300;
    for (double sign : {-1.0, 1.0}) {  // the turn's sign is the build's (a box is symmetric)
      const Eigen::Matrix3d Rt = Eigen::AngleAxisd(sign * t * turn_degrees * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      double worst = 0;
      for (int v = 0; v < s.mesh.V.rows(); ++v) {
        const Eigen::Vector3d p = Rt.transpose() * (s.mesh.V.row(v).transpose() - t * shift);
        const Eigen::Vector3d d = p.cwiseAbs() - Eigen::Vector3d(2, 0.5, 0.5);
        worst = std::max(worst, std::abs(d.cwiseMax(0).norm() + std::min(d.maxCoeff(), 0.0)));
      }
      best = std::min(best, worst);
    }
    std::printf("  t %.2f: farthest from the turned box %.4f (%.2f%% of its diagonal), volume %.4f (%.2f%% off)\n", t, best,
                100 * best / std::sqrt(18.0), enclosed_volume(s.mesh.V, s.mesh.F), 25 * std::abs(enclosed_volume(s.mesh.V, s.mesh.F) - 4));
  }
}

// Issue 30: the teddy (assets/default.obj) to assets/key-torus.obj with five picked pairs (hands and
// feet to the ring's diagonals, head to its top; docs/transition_pairs_demo.txt), against the same
// keys with the picked pairs alone and without pairs in the same process: the warp's cost (align and
// place) with its eight steps and the closest-point pairs, and the in-between's volume at t = 0.5.
void picked_pairs() {
  const std::string dir = DFM_SOURCE_DIR;
  const TriMesh teddy = read_surface(dir + "/assets/default.obj"), ring = read_surface(dir + "/assets/key-torus.obj");
  const double c = 0.95 / std::sqrt(2.0);
  Eigen::MatrixXd pairs(5, 6);
  pairs << 1.1288187236885718, 0.048088046705787896, -0.016957917920236727, c, c, 0,  //
      -1.129240817223571, 0.05504727195426104, 0.0008706785716474283, -c, c, 0,      //
      0.23826135347593744, 1.289253208047552, 0.013253281806088448, 0, 0.95, 0,      //
      0.237840569022293, -1.238521524130062, 0.08905058984878422, c, -c, 0,          //
      -0.24126803967534724, -1.238687533855284, 0.04842943221220615, -c, -c, 0;
  TransitionStats with, alone, without;
  TransitionOptions o;
  build_transition(teddy, 0, ring, 1, o, &without);
  o.pairs = pairs;
  o.elastic_samples = 0;
  const AnimationManifold A = build_transition(teddy, 0, ring, 1, o, &alone);
  o.elastic_samples = TransitionOptions{}.elastic_samples;
  const AnimationManifold M = build_transition(teddy, 0, ring, 1, o, &with);
  auto volume = [](const AnimationManifold& m) {
    const TriMesh s = slice_manifold(m, SliceAxis::T, 0.5).mesh;
    return enclosed_volume(s.V, s.F);
  };
  std::printf("teddy to ring, 5 pairs and %d closest-point pairs: total %.2f s, align and place %.2f s (%d vertices placed), "
              "slice at 0.5: %d triangles, volume %.3f\n",
              with.elastic_pairs, with.total_seconds, with.align_seconds, M.num_vertices(),
              static_cast<int>(slice_manifold(M, SliceAxis::T, 0.5).mesh.F.rows()), volume(M));
  std::printf("%-28s picked pairs alone: total %.2f s, align and place %.2f s, volume at 0.5 %.3f; no pairs: total %.2f s, "
              "align and place %.2f s; keys' volumes %.3f, %.3f\n",
              "", alone.total_seconds, alone.align_seconds, volume(A), without.total_seconds, without.align_seconds,
              enclosed_volume(teddy.V, teddy.F), enclosed_volume(ring.V, ring.F));
}

}  // namespace

int main() {
  const TriMesh torus = dfm::test::torus(Eigen::Vector3d::Zero(), 0.32, 0.12, 100, 50);  // 5,000 vertices, genus 1
  const TriMesh two = dfm::test::concat(dfm::test::icosphere(Eigen::Vector3d(-0.22, 0, 0), 0.2, 4),
                                        dfm::test::icosphere(Eigen::Vector3d(0.22, 0, 0.01), 0.2, 4));  // 5,124
  for (bool align : {false, true}) {
    run("torus to two spheres", torus, two, align);
    run("icosphere 2562 to torus", dfm::test::icosphere(Eigen::Vector3d::Zero(), 0.45, 4), torus, align);
    try {
      const std::string dir = DFM_DATA_DIR;
      run("bunny to 3holes", dfm::test::into_unit_box(read_surface(dir + "/bunny.off")),
          dfm::test::into_unit_box(read_surface(dir + "/3holes.off")), align);
    } catch (const std::exception& e) {
      std::printf("bunny to 3holes skipped: %s\n", e.what());
    }
  }
  picked_pairs();
  // Issue 30: a quarter turn over 4 layers (22.5 degrees each), 8 (the default, 15 per layer) and 12.
  turn(1.0 / 16, 0, 15);
  for (double max_turn : {22.5, 15.0, 10.0}) turn(1.0 / 16, 90, max_turn);
  return 0;
}
