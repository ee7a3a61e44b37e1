#include "core/anim/layer_transients.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include "core/anim/transition_points.h"

namespace dfm {
namespace {

struct Crossing {
  int point = -1;
  double time = 0;     // u where the point's sign changes
  int layer = -1;      // the last layer before it
  bool joins = false;  // inside after it
};

struct Change {
  double time = 0;
  int point = -1;
  int euler = 0;  // of the inside set
};

// Each point's one sign change over the layers, by time.
std::vector<Crossing> crossings(const std::vector<double>& u, const std::vector<Eigen::VectorXd>& values) {
  std::vector<Crossing> out;
  for (Eigen::Index p = 0; p < values.front().size(); ++p)
    for (size_t k = 0; k + 1 < values.size(); ++k) {
      const double a = values[k][p], b = values[k + 1][p];
      if ((a < 0) == (b < 0)) continue;
      out.push_back({static_cast<int>(p), u[k] + (u[k + 1] - u[k]) * a / (a - b), static_cast<int>(k), b < 0});
      break;
    }
  std::stable_sort(out.begin(), out.end(), [](const Crossing& a, const Crossing& b) { return a.time < b.time; });
  return out;
}

// The Euler characteristic of p's link restricted to inside points.
int inside_link_euler(const MatrixX4iRow& K, const std::vector<int>& star, int p, const std::vector<char>& inside) {
  std::vector<int> points;
  std::vector<std::pair<int, int>> edges;
  int triangles = 0;
  for (int t : star) {
    int f[3], n = 0;
    for (int c = 0; c < 4; ++c)
      if (K(t, c) != p) f[n++] = K(t, c);
    for (int a = 0; a < 3; ++a) {
      const int b = (a + 1) % 3;
      if (inside[f[a]]) points.push_back(f[a]);
      if (inside[f[a]] && inside[f[b]]) edges.emplace_back(std::min(f[a], f[b]), std::max(f[a], f[b]));
    }
    triangles += inside[f[0]] && inside[f[1]] && inside[f[2]];
  }
  std::sort(points.begin(), points.end());
  std::sort(edges.begin(), edges.end());
  const auto v = std::unique(points.begin(), points.end()) - points.begin();
  const auto e = std::unique(edges.begin(), edges.end()) - edges.begin();
  return static_cast<int>(v - e) + triangles;
}

// The sweep's topology changes, in time order.
std::vector<Change> sweep_changes(const MatrixX4iRow& K, Eigen::Index n, const std::vector<Crossing>& cross,
                                  const Eigen::VectorXd& first) {
  std::vector<std::vector<int>> star(static_cast<size_t>(n));
  for (Eigen::Index t = 0; t < K.rows(); ++t)
    for (int c = 0; c < 4; ++c) star[K(t, c)].push_back(static_cast<int>(t));
  std::vector<char> inside(static_cast<size_t>(n));
  for (Eigen::Index p = 0; p < n; ++p) inside[p] = first[p] < 0;
  std::vector<Change> out;
  for (const Crossing& c : cross) {
    const int chi = inside_link_euler(K, star[c.point], c.point, inside);
    const int euler = c.joins ? 1 - chi : chi - 1;
    inside[c.point] = c.joins;
    if (euler != 0) out.push_back({c.time, c.point, euler});
  }
  return out;
}

// Each change paired with the next opposite one within radius and max_life.
std::vector<std::pair<int, int>> short_lived(const Eigen::MatrixXd& X, const std::vector<Change>& changes,
                                             const LayerTransientOptions& o) {
  const double r2 = o.radius * o.radius;
  std::vector<std::pair<int, int>> pairs;
  std::vector<char> used(changes.size());
  for (size_t i = 0; i < changes.size(); ++i) {
    if (used[i]) continue;
    for (size_t j = i + 1; j < changes.size() && changes[j].time - changes[i].time <= o.max_life; ++j)
      if (!used[j] && changes[j].euler == -changes[i].euler &&
          (X.row(changes[i].point) - X.row(changes[j].point)).squaredNorm() <= r2) {
        used[i] = used[j] = 1;
        pairs.emplace_back(static_cast<int>(i), static_cast<int>(j));
        break;
      }
  }
  return pairs;
}

// Pairs grouped into events: connected when any of their changes lie within radius.
std::vector<std::vector<int>> events_of(const Eigen::MatrixXd& X, const std::vector<Change>& changes,
                                        const std::vector<std::pair<int, int>>& pairs, double radius) {
  std::vector<int> parent(pairs.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  const double r2 = radius * radius;
  for (size_t i = 0; i < pairs.size(); ++i)
    for (size_t j = i + 1; j < pairs.size(); ++j)
      for (int a : {pairs[i].first, pairs[i].second})
        for (int b : {pairs[j].first, pairs[j].second})
          if ((X.row(changes[a].point) - X.row(changes[b].point)).squaredNorm() <= r2)
            parent[root(static_cast<int>(i))] = root(static_cast<int>(j));
  std::vector<std::vector<int>> events(pairs.size());
  for (size_t i = 0; i < pairs.size(); ++i)
    for (int c : {pairs[i].first, pairs[i].second}) events[root(static_cast<int>(i))].push_back(c);
  events.erase(std::remove_if(events.begin(), events.end(), [](const std::vector<int>& e) { return e.empty(); }), events.end());
  return events;
}

// The sweep's crossings, its topology changes and the short-lived events among them.
struct Sweep {
  std::vector<Crossing> cross;
  std::vector<Change> changes;
  std::vector<std::vector<int>> events;  // indices into changes
};

Sweep sweep(const Eigen::MatrixXd& X, const MatrixX4iRow& K, const std::vector<double>& u,
            const std::vector<Eigen::VectorXd>& values, const LayerTransientOptions& o) {
  Sweep s;
  if (values.size() < 2 || o.max_life <= 0 || o.radius <= 0) return s;
  s.cross = crossings(u, values);
  s.changes = sweep_changes(K, X.rows(), s.cross, values.front());
  s.events = events_of(X, s.changes, short_lived(X, s.changes, o), o.radius);
  return s;
}

}  // namespace

std::vector<int> layer_transient_points(const Eigen::MatrixXd& X, const MatrixX4iRow& K, const std::vector<double>& u,
                                        const std::vector<Eigen::VectorXd>& values, const LayerTransientOptions& o) {
  const Sweep s = sweep(X, K, u, values, o);
  std::vector<int> points;
  for (const std::vector<int>& event : s.events)
    for (int c : event) points.push_back(s.changes[c].point);
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  return points;
}

LayerTransientStats merge_layer_transients(const Eigen::MatrixXd& X, const MatrixX4iRow& K, const std::vector<double>& u,
                                           std::vector<Eigen::VectorXd>& values, double away,
                                           const LayerTransientOptions& o) {
  LayerTransientStats st;
  const Sweep s = sweep(X, K, u, values, o);
  const std::vector<Crossing>& cross = s.cross;
  const std::vector<Change>& changes = s.changes;
  const double r2 = o.radius * o.radius;
  for (const std::vector<int>& event : s.events) {
    double start = changes[event.front()].time, end = start;
    for (int c : event) start = std::min(start, changes[c].time), end = std::max(end, changes[c].time);
    ++st.events;
    std::vector<const Crossing*> moved;
    std::vector<double> rates;
    for (const Crossing& x : cross) {
      if (x.time < start || x.time > end) continue;
      if (std::any_of(event.begin(), event.end(), [&](int c) { return (X.row(x.point) - X.row(changes[c].point)).squaredNorm() <= r2; })) {
        moved.push_back(&x);
        rates.push_back(std::abs(values[x.layer + 1][x.point] - values[x.layer][x.point]) / (u[x.layer + 1] - u[x.layer]));
      }
    }
    // One rate for all: the staircase's 4-simplices among moved points then cross exactly at the start.
    std::nth_element(rates.begin(), rates.begin() + rates.size() / 2, rates.end());
    const double rate = rates[rates.size() / 2];
    // The layers from the last before the start to the first after the end; the others keep their
    // values, which have the same signs.
    size_t first = 0, last = u.size() - 1;
    while (first + 1 < u.size() && u[first + 1] <= start) ++first;
    while (last > 0 && u[last - 1] > end) --last;
    for (const Crossing* x : moved) {
      for (size_t l = first; l <= last; ++l) {
        values[l][x->point] = transition_detail::clamp_away_from_zero((x->joins ? -rate : rate) * (u[l] - start), away);
      }
      ++st.moved;
    }
  }
  return st;
}

}  // namespace dfm
