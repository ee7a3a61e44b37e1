#include "core/anim/manifold_refine.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>
#include <vector>

#include "core/anim/manifold_retime.h"
#include "core/mesh/red_green_refine.h"
#include "core/util/error.h"

namespace dfm {

namespace {

// The first manifold vertex of layer `layer` of a prism manifold.
int layer_start(const AnimationManifold& m, int layer) {
  return layer < m.num_slabs() ? m.prism_slabs[layer].lower : m.prism_slabs[layer - 1].upper;
}

// A prism manifold's layer mesh: its triangles and each layer's positions (x, y, z).
struct Layers {
  Eigen::MatrixXi F;
  std::vector<Eigen::MatrixXd> V;
};

Layers layers_of(const AnimationManifold& m) {
  const int ns = m.num_slabs();
  if (ns < 1 || m.prism_slabs.size() != static_cast<size_t>(ns) || !m.key_layers.empty())
    throw Error("space-time refinement needs a manifold of prism layers of one mesh (no transition)");
  const PrismSlab& first = m.prism_slabs.front();
  for (int s = 0; s < ns; ++s) {
    const PrismSlab& p = m.prism_slabs[s];
    if (!p.is_prism() || p.faces != first.faces || p.count != first.count ||
        (s > 0 && p.lower != m.prism_slabs[s - 1].upper))
      throw Error("space-time refinement needs a manifold of prism layers of one mesh (no transition, no retime)");
  }
  Layers L;
  L.F = m.layer_faces[first.faces];
  for (int s = 0; s <= ns; ++s) {
    L.V.push_back(m.V.block(layer_start(m, s), 0, first.count, 3));
  }
  if (m.num_vertices() != first.count * (ns + 1))
    throw Error("space-time refinement needs a manifold of prism layers of one mesh (no other vertex)");
  return L;
}

// Calls fn(f, a, b) for each edge (a, b) of layer triangle f, in every layer, with an end in `region`
// (manifold vertex indices).
template <class Fn>
void for_region_layer_edges(const AnimationManifold& m, const std::vector<int>& region, Fn fn) {
  const Eigen::MatrixXi& F = m.layer_faces[m.prism_slabs.front().faces];
  std::vector<char> in(static_cast<size_t>(m.num_vertices()), 0);
  for (int v : region) in[v] = 1;
  for (int layer = 0; layer < m.num_layers(); ++layer) {
    const int start = layer_start(m, layer);
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      for (int j = 0; j < 3; ++j) {
        const int a = start + F(f, j), b = start + F(f, (j + 1) % 3);
        if (in[a] || in[b]) fn(f, a, b);
      }
  }
}

// The mean length of the layer edges at region vertices.
double mean_region_edge(const AnimationManifold& m, const std::vector<int>& region) {
  double sum = 0;
  int count = 0;
  for_region_layer_edges(m, region, [&](Eigen::Index, int a, int b) { sum += (m.V.row(a) - m.V.row(b)).head<3>().norm(), ++count; });
  return count > 0 ? sum / count : 0;
}

// The layer triangles with an edge at a region vertex that `edited` stretched past stretch x mean (in any
// layer).
std::vector<char> stretched_triangles(const AnimationManifold& m, const MatrixX4dRow& edited, const std::vector<int>& region,
                                      double mean, double stretch, double* longest) {
  std::vector<char> red(static_cast<size_t>(m.layer_faces[m.prism_slabs.front().faces].rows()), 0);
  *longest = 0;
  if (mean <= 0) return red;
  for_region_layer_edges(m, region, [&](Eigen::Index f, int a, int b) {
    const double after = (edited.row(a) - edited.row(b)).head<3>().norm();
    *longest = std::max(*longest, after / mean);
    if (after > stretch * mean && after > (m.V.row(a) - m.V.row(b)).head<3>().norm()) red[f] = 1;
  });
  return red;
}

// `marked` and `rings` rings of triangles around it (sharing a vertex).
std::vector<char> with_rings(const Eigen::MatrixXi& F, int num_vertices, std::vector<char> marked, int rings) {
  for (int k = 0; k < rings; ++k) {
    std::vector<char> touched(static_cast<size_t>(num_vertices), 0);
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      if (marked[f])
        for (int j = 0; j < 3; ++j) touched[F(f, j)] = 1;
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      for (int j = 0; j < 3; ++j) marked[f] = marked[f] || touched[F(f, j)];
  }
  return marked;
}

// The prism build orders each triangle's vertices by index to pick its staircase, and a vertex's time
// edges go to the next layer's copies of its lower-numbered neighbours. Middles appended after every
// original vertex would all get one-sided time stencils (up to every neighbour, down to none), which
// the Laplacian turns into ripples on frames between layers. So each middle is numbered between its
// edge's ends: original vertex v sorts at 2v, the middle of (a, b) at a + b + 1/2. rank[v] is the new
// number of vertex v (originals first, then middles, as red_green_refine numbers them).
std::vector<int> interleaved_order(int count, const std::vector<std::array<int, 2>>& middles) {
  const int n0 = count;
  const int n = n0 + static_cast<int>(middles.size());
  std::vector<double> key(static_cast<size_t>(n));
  for (int v = 0; v < n0; ++v) key[v] = 2.0 * v;
  for (size_t i = 0; i < middles.size(); ++i) key[n0 + i] = middles[i][0] + middles[i][1] + 0.5;
  std::vector<int> order(static_cast<size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key[a] < key[b]; });
  std::vector<int> rank(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) rank[order[i]] = i;
  return rank;
}

Eigen::MatrixXd permute_rows(const Eigen::MatrixXd& V, const std::vector<int>& rank) {
  Eigen::MatrixXd out(V.rows(), V.cols());
  for (Eigen::Index v = 0; v < V.rows(); ++v) out.row(rank[v]) = V.row(v);
  return out;
}

AnimationManifold edit_once(const AnimationManifold& m, const EditRegionSpec& region, const EditHandleSpec& handle,
                            const ManifoldEditOptions& options, const ManifoldDrag& drag, std::vector<int>* selected) {
  EditRegion sel = select_edit_region(m, region, handle);
  *selected = sel.region;
  AnimationManifold out = m;
  out.V = ManifoldEditor(m, std::move(sel), handle.point, options).drag(drag);
  return out;
}

}  // namespace

void check_refinable(const AnimationManifold& m) { layers_of(m); }

AnimationManifold edit_refined(const AnimationManifold& m, const EditRegionSpec& region, const EditHandleSpec& handle,
                               const ManifoldEditOptions& options, const ManifoldDrag& drag, const RefineOptions& refine,
                               RefineStats* stats) {
  if (!(refine.stretch > 1) || refine.max_rounds < 0)
    throw Error("space-time refinement: the stretch tolerance must exceed 1 and the rounds be at least 0");
  Layers layers = layers_of(m);
  RefineStats st;
  st.layer_index.resize(static_cast<size_t>(layers.V.front().rows()));
  std::iota(st.layer_index.begin(), st.layer_index.end(), 0);
  AnimationManifold base = m;
  std::vector<int> selected;
  AnimationManifold out = edit_once(base, region, handle, options, drag, &selected);
  // Lengths are judged against the unrefined mesh's, so later rounds split only what is still long.
  const double mean = mean_region_edge(base, selected);
  for (int round = 0;; ++round) {
    const std::vector<char> red = stretched_triangles(base, out.V, selected, mean, refine.stretch, &st.longest);
    if (round == refine.max_rounds || std::find(red.begin(), red.end(), 1) == red.end()) break;
    const int n = static_cast<int>(layers.V.front().rows());
    const RedGreenRefinement r = red_green_refine(layers.F, n, with_rings(layers.F, n, red, refine.rings));
    layers.F.resize(r.F.rows(), 3);
    const std::vector<int> rank = interleaved_order(n, r.middles);
    for (Eigen::MatrixXd& V : layers.V) V = permute_rows(append_middles(V, r.middles), rank);
    for (Eigen::Index f = 0; f < r.F.rows(); ++f)
      for (int j = 0; j < 3; ++j) layers.F(f, j) = rank[r.F(f, j)];
    for (int& v : st.layer_index) v = rank[v];
    st.added += static_cast<int>(r.middles.size());
    ++st.rounds;
    base = build_manifold(layers.V, layers.F, m.times);
    out = edit_once(base, region, handle, options, drag, &selected);
  }
  if (drag.retime != 0) merge_retimed_slabs(out);
  if (stats) *stats = st;
  return out;
}

}  // namespace dfm
