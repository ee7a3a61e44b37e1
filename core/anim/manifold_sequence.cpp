#include "core/anim/manifold_sequence.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <list>
#include <mutex>

#include "core/util/error.h"

namespace dfm {

bool same_connectivity(const KeySurface& a, const KeySurface& b) {
  return a.V.rows() == b.V.rows() && a.F.rows() == b.F.rows() && a.F == b.F;
}

namespace {

// Transitions take seconds, and the editor's view, its saves and the script ask for the same ones:
// the last few are kept, found by exact comparison of both keys, their times and the options.
class TransitionCache {
 public:
  AnimationManifold get(const KeySurface& a, const KeySurface& b, const TransitionOptions& o, TransitionStats* st) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (auto it = entries_.begin(); it != entries_.end(); ++it)
        if (it->matches(a, b, o)) {
          entries_.splice(entries_.begin(), entries_, it);  // most recent first
          *st = entries_.front().stats;
          return entries_.front().manifold;
        }
    }
    Entry e{a, b, o, {}, {}};
    e.manifold = build_transition({a.V, a.F, {}}, a.time, {b.V, b.F, {}}, b.time, o, &e.stats);
    *st = e.stats;
    std::lock_guard<std::mutex> lock(mutex_);
    entries_.push_front(std::move(e));
    if (entries_.size() > kCapacity) entries_.pop_back();
    return entries_.front().manifold;
  }

 private:
  static constexpr size_t kCapacity = 4;
  struct Entry {
    KeySurface a, b;
    TransitionOptions options;
    AnimationManifold manifold;
    TransitionStats stats;
    bool matches(const KeySurface& x, const KeySurface& y, const TransitionOptions& o) const {
      auto same = [](const KeySurface& p, const KeySurface& q) {
        return p.time == q.time && p.V.rows() == q.V.rows() && p.F.rows() == q.F.rows() && p.V == q.V && p.F == q.F;
      };
      return same(a, x) && same(b, y) && options == o;
    }
  };
  std::mutex mutex_;
  std::list<Entry> entries_;
};

TransitionCache& transition_cache() {
  static TransitionCache cache;
  return cache;
}

// Appends M's slabs (vertices renumbered after out's) to out.
void append_slabs(AnimationManifold& out, const AnimationManifold& M) {
  const int base_v = out.num_vertices(), base_t = out.num_tets();
  out.V.conservativeResize(base_v + M.num_vertices(), 4);
  out.V.bottomRows(M.num_vertices()) = M.V;
  out.T.conservativeResize(base_t + M.num_tets(), 4);
  out.T.bottomRows(M.num_tets()) = M.T.array() + base_v;
  const bool first = out.times.empty();
  for (int i = first ? 0 : 1; i < M.num_layers(); ++i) {
    out.times.push_back(M.times[i]);
    out.slab_offsets.push_back(base_t + M.slab_offsets[i]);
  }
  // How each slab was made, renumbered the same way (a transition's slabs have no prism entry).
  const int base_f = static_cast<int>(out.layer_faces.size());
  for (int i = 0; i < M.num_slabs(); ++i) {
    PrismSlab p = M.prism_slabs.empty() ? PrismSlab{} : M.prism_slabs[i];
    if (p.is_prism()) {
      p.faces += base_f;
      p.lower += base_v;
      p.upper += base_v;
    }
    out.prism_slabs.push_back(p);
  }
  out.layer_faces.insert(out.layer_faces.end(), M.layer_faces.begin(), M.layer_faces.end());
}

// The key as it stands in out's vertices [first, out.num_vertices()) at its time: each key vertex's
// manifold vertex (within 1e-9 of the key's bounding-box diagonal; a transition keeps every key
// vertex). False, out unchanged, when a vertex has none (e.g. an unreferenced one the build dropped).
bool add_key_layer(AnimationManifold& out, int first, const KeySurface& key) {
  std::vector<std::pair<double, int>> by_x;  // candidates at the key's time, sorted by x
  for (int v = first; v < out.num_vertices(); ++v)
    if (out.V(v, 3) == key.time) by_x.push_back({out.V(v, 0), v});
  std::sort(by_x.begin(), by_x.end());
  const double tol = 1e-9 * (key.V.colwise().maxCoeff() - key.V.colwise().minCoeff()).norm();
  ManifoldKey layer{key.time, static_cast<int>(out.layer_faces.size()), std::vector<int>(key.V.rows(), -1)};
  for (Eigen::Index k = 0; k < key.V.rows(); ++k) {
    double best = tol;
    for (auto it = std::lower_bound(by_x.begin(), by_x.end(), std::make_pair(key.V(k, 0) - tol, -1));
         it != by_x.end() && it->first <= key.V(k, 0) + tol; ++it) {
      const double d = (out.V.block<1, 3>(it->second, 0) - key.V.row(k)).norm();
      if (d <= best) best = d, layer.vertices[k] = it->second;
    }
    if (layer.vertices[k] < 0) return false;
  }
  out.layer_faces.push_back(key.F);
  out.key_layers.push_back(std::move(layer));
  return true;
}

}  // namespace

AnimationManifold build_manifold_sequence(const std::vector<KeySurface>& keys, const TransitionOptions& options,
                                          SequenceStats* stats, const std::function<bool(int, int)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  const int m = static_cast<int>(keys.size());
  if (m < 2) throw Error("an animation manifold needs at least 2 keys, got " + std::to_string(m));
  for (int i = 0; i < m; ++i) {
    if (!std::isfinite(keys[i].time) || (i > 0 && !(keys[i].time > keys[i - 1].time)))
      throw Error("key times must be finite and strictly increasing (" + keys[i].name + ")");
    if (keys[i].V.cols() != 3 || keys[i].F.cols() != 3)
      throw Error(keys[i].name + ": positions and triangles need 3 columns");
  }
  SequenceStats local;
  AnimationManifold out;
  out.V.resize(0, 4);
  out.T.resize(0, 4);
  int i = 0;
  while (i + 1 < m) {
    int j = i;  // the run [i, j] of keys sharing one triangle list
    while (j + 1 < m && same_connectivity(keys[j], keys[j + 1])) ++j;
    if (j > i) {
      std::vector<Eigen::MatrixXd> layers;
      std::vector<double> times;
      for (int k = i; k <= j; ++k) {
        layers.push_back(keys[k].V);
        times.push_back(keys[k].time);
      }
      append_slabs(out, build_manifold(layers, keys[i].F, times));
      local.prism_slabs += j - i;
      i = j;
    } else {
      TransitionStats ts;
      check_transition_key({keys[i].V, keys[i].F, {}}, keys[i].name);
      check_transition_key({keys[i + 1].V, keys[i + 1].F, {}}, keys[i + 1].name);
      TransitionOptions o = options;
      if (keys[i].pairs_to_next.rows() > 0) o.pairs = keys[i].pairs_to_next;
      const int first = out.num_vertices();
      try {
        append_slabs(out, transition_cache().get(keys[i], keys[i + 1], o, &ts));
      } catch (const Error& e) {
        throw Error(keys[i].name + " to " + keys[i + 1].name + ": " + e.what());
      }
      add_key_layer(out, first, keys[i]);
      add_key_layer(out, first, keys[i + 1]);
      local.transition_slabs += 1;
      local.transitions += ts;
      i += 1;
    }
    if (progress && !progress(i, m - 1)) throw Cancelled("animation manifold build cancelled");
  }
  local.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (stats) *stats = local;
  validate_manifold(out, "animation manifold");
  return out;
}

}  // namespace dfm
