#include "core/anim/manifold_retime.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <unordered_set>

#include "core/util/error.h"

namespace dfm {

std::vector<std::array<int, 2>> prism_time_edges(const AnimationManifold& m, const std::vector<int>& vertices) {
  if (m.prism_slabs.size() != static_cast<size_t>(m.num_slabs()) || m.num_slabs() == 0)
    throw Error("the manifold was not built from layers (no prism slabs)");
  const std::unordered_set<int> set(vertices.begin(), vertices.end());
  std::vector<std::array<int, 2>> edges;
  for (int v : vertices)
    if (m.V(v, 3) <= m.times.front() || m.V(v, 3) >= m.times.back())
      throw Error("vertex " + std::to_string(v) + " is on the animation's first or last layer, which bounds it in time");
  for (int s = 0; s < m.num_slabs(); ++s) {
    const PrismSlab& p = m.prism_slabs[s];
    if (!p.is_prism()) {
      for (int k = m.slab_offsets[s]; k < m.slab_offsets[s + 1]; ++k)
        for (int j = 0; j < 4; ++j)
          if (set.count(m.T(k, j)))
            throw Error("vertex " + std::to_string(m.T(k, j)) + " is in slab " + std::to_string(s) +
                        ", which is not made of prisms (a transition)");
      continue;
    }
    for (int v : vertices) {
      if (v >= p.lower && v < p.lower + p.count) edges.push_back({v, p.upper + (v - p.lower)});
      if (v >= p.upper && v < p.upper + p.count) edges.push_back({p.lower + (v - p.upper), v});
    }
  }
  return edges;
}

void check_time_edges(const MatrixX4dRow& V, const std::vector<std::array<int, 2>>& edges) {
  for (const auto& e : edges)
    if (!(V(e[1], 3) > V(e[0], 3))) {
      char buf[200];
      std::snprintf(buf, sizeof buf, "the retime folds the manifold in time: vertex %d (t = %.6g) is not after vertex %d "
                    "(t = %.6g) below it; retime less", e[1], V(e[1], 3), e[0], V(e[0], 3));
      throw Error(buf);
    }
}

void merge_retimed_slabs(AnimationManifold& m) {
  const int ns = m.num_slabs();
  std::vector<double> lo(ns, 0), hi(ns, 0);
  for (int s = 0; s < ns; ++s) {
    lo[s] = m.times[s + 1];
    hi[s] = m.times[s];
    for (int k = m.slab_offsets[s]; k < m.slab_offsets[s + 1]; ++k)
      for (int j = 0; j < 4; ++j) lo[s] = std::min(lo[s], m.V(m.T(k, j), 3)), hi[s] = std::max(hi[s], m.V(m.T(k, j), 3));
  }
  auto layer_at_time = [&](int first, int count, double t) {
    for (int v = first; v < first + count; ++v)
      if (m.V(v, 3) != t) return false;
    return true;
  };
  std::vector<PrismSlab> prisms = m.prism_slabs;
  for (int s = 0; s < static_cast<int>(prisms.size()); ++s)
    if (prisms[s].is_prism() && !(layer_at_time(prisms[s].lower, prisms[s].count, m.times[s]) &&
                                  layer_at_time(prisms[s].upper, prisms[s].count, m.times[s + 1])))
      prisms[s] = PrismSlab{};
  // Layer time i (between slabs i - 1 and i) stays when neither slab crosses it.
  std::vector<double> times{m.times.front()};
  std::vector<int> offsets{0};
  std::vector<PrismSlab> merged_prisms;
  bool merging = false;
  for (int s = 0; s < ns; ++s) {
    if (merging) {
      offsets.back() = m.slab_offsets[s + 1];
      times.back() = m.times[s + 1];
      if (!merged_prisms.empty()) merged_prisms.back() = PrismSlab{};
    } else {
      offsets.push_back(m.slab_offsets[s + 1]);
      times.push_back(m.times[s + 1]);
      if (!prisms.empty()) merged_prisms.push_back(prisms[s]);
    }
    merging = s + 1 < ns && (hi[s] > m.times[s + 1] || lo[s + 1] < m.times[s + 1]);
  }
  std::vector<ManifoldKey> keys;
  for (const ManifoldKey& k : m.key_layers) {
    if (!std::binary_search(times.begin(), times.end(), k.time)) continue;
    bool on = true;
    for (int v : k.vertices) on = on && m.V(v, 3) == k.time;
    if (on) keys.push_back(k);
  }
  m.times = std::move(times);
  m.slab_offsets = std::move(offsets);
  m.prism_slabs = std::move(merged_prisms);
  m.key_layers = std::move(keys);
  validate_manifold(m, "retimed manifold");
}

}  // namespace dfm
