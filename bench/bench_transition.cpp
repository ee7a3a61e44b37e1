// Transition build between keys of different topology (Southern 2008, 8.7.1: a 3,000-vertex
// fertility model to a sphere took about 800 s: fill 12.2 s, find 559.5 s, strip 227.1 s).
// Pairs of about 5K vertices each; prints each stage, then the cost of slicing the result next to
// slicing a prism manifold of the same size in tetrahedra (the same CPU slicer).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>

#include "core/anim/manifold.h"
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

void run(const char* name, const TriMesh& a, const TriMesh& b) {
  TransitionStats st;
  const AnimationManifold M = build_transition(a, 0, b, 1, {}, &st);
  std::printf("%-28s %5d -> %5d vertices: total %.2f s (conform and fill %.2f, field %.2f, delaunay %.2f, extract %.2f); "
              "%d + %d + %d points, %d 4-simplices, %d Steiner points, %d flips, %d triangles not conforming, %d chords, %d key-plane fixes, %d tets\n",
              name, static_cast<int>(a.V.rows()), static_cast<int>(b.V.rows()), st.total_seconds, st.conform_seconds,
              st.field_seconds, st.delaunay_seconds, st.extract_seconds, st.source_points, st.middle_points,
              st.target_points, st.simplices, st.source_steiner + st.target_steiner, st.source_flipped + st.target_flipped,
              st.source_missing + st.target_missing, st.source_chords + st.target_chords,
              st.source_plane_fixes + st.target_plane_fixes, st.tets);
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

}  // namespace

int main() {
  const TriMesh torus = dfm::test::torus(Eigen::Vector3d::Zero(), 0.32, 0.12, 100, 50);  // 5,000 vertices, genus 1
  const TriMesh two = dfm::test::concat(dfm::test::icosphere(Eigen::Vector3d(-0.22, 0, 0), 0.2, 4),
                                        dfm::test::icosphere(Eigen::Vector3d(0.22, 0, 0.01), 0.2, 4));  // 5,124
  run("torus to two spheres", torus, two);
  run("icosphere 2562 to torus", dfm::test::icosphere(Eigen::Vector3d::Zero(), 0.45, 4), torus);
  try {
    const std::string dir = DFM_DATA_DIR;
    run("bunny to 3holes", dfm::test::into_unit_box(read_surface(dir + "/bunny.off")),
        dfm::test::into_unit_box(read_surface(dir + "/3holes.off")));
  } catch (const std::exception& e) {
    std::printf("bunny to 3holes skipped: %s\n", e.what());
  }
  return 0;
}
