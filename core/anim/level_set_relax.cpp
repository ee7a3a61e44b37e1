#include "core/anim/level_set_relax.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "core/anim/manifold_normals.h"
#include "core/bind/parallel_for.h"
#include "core/util/error.h"
#include "core/util/huge_pages.h"

namespace dfm {

namespace {

// The 4D normal of tetrahedron t (manifold_normals.h's tet_normal4), t scaled.
Eigen::Vector4d normal4(const MatrixX4dRow& V, const int* t, double time_scale) {
  Eigen::Vector4d e[3];
  for (int k = 0; k < 3; ++k) {
    e[k] = (V.row(t[k + 1]) - V.row(t[0])).transpose();
    e[k][3] *= time_scale;
  }
  return cross4(e[0], e[1], e[2]);
}

// Whether a tetrahedron with normal n before has turned over with normal m after: in 4D, or in the
// spatial part a slice's triangle takes its normal from (unless that part is negligible before).
bool turned(const Eigen::Vector4d& n, const Eigen::Vector4d& m) {
  if (!(n.dot(m) > 0)) return true;
  return n.head<3>().norm() > 1e-3 * n.norm() && !(n.head<3>().dot(m.head<3>()) > 0);
}

// Compressed rows: items[begin[i], begin[i + 1]) belong to i.
struct Rows {
  std::vector<int> begin, items;
};

// Visited marks: this thread's array (at least n long), stamped with values from `epoch`, unique over
// rounds and calls, so never reset.
std::atomic<long long> epoch{0};
std::vector<long long>& thread_stamps(int n) {
  thread_local std::vector<long long> stamp;
  if (stamp.size() < static_cast<size_t>(n)) stamp.assign(n, -1);
  return stamp;
}

// Each vertex's tetrahedra, in index order: items[begin[v], begin[v + 1]).
Rows vertex_tets(const MatrixX4iRow& T, int nv) {
  Rows r;
  r.begin.assign(nv + 1, 0);
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    for (int c = 0; c < 4; ++c) ++r.begin[T(t, c) + 1];
  for (int v = 0; v < nv; ++v) r.begin[v + 1] += r.begin[v];
  reserve_huge(r.items, r.begin[nv]);
  r.items.resize(r.begin[nv]);
  std::vector<int> fill(r.begin.begin(), r.begin.end() - 1);
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    for (int c = 0; c < 4; ++c) r.items[fill[T(t, c)]++] = static_cast<int>(t);
  return r;
}

// Each vertex's neighbours, each once, in the order its tetrahedra (`tets`) show them.
Rows neighbours(const MatrixX4iRow& T, const Rows& tets) {
  const int nv = static_cast<int>(tets.begin.size()) - 1;
  const long long base = epoch.fetch_add(2LL * nv);
  // Calls out(w) for each neighbour w of v, once, marked with `mark`.
  auto each = [&](int v, long long mark, const auto& out) {
    std::vector<long long>& stamp = thread_stamps(nv);
    for (int k = tets.begin[v]; k < tets.begin[v + 1]; ++k) {
      const int* t = T.row(tets.items[k]).data();
      int c = 0;
      while (t[c] != v) ++c;
      for (int d = 1; d < 4; ++d) {
        const int w = t[(c + d) % 4];
        if (stamp[w] != mark) stamp[w] = mark, out(w);
      }
    }
  };
  Rows r;
  r.begin.assign(nv + 1, 0);
  parallel_for(nv, 0, [&](int v) { each(v, base + v, [&](int) { ++r.begin[v + 1]; }); });
  for (int v = 0; v < nv; ++v) r.begin[v + 1] += r.begin[v];
  reserve_huge(r.items, r.begin[nv]);
  r.items.resize(r.begin[nv]);
  parallel_for(nv, 0, [&](int v) {
    int k = r.begin[v];
    each(v, base + nv + v, [&](int w) { r.items[k++] = w; });
  });
  return r;
}

}  // namespace

LevelSetRelaxStats relax_level_set(MatrixX4dRow& V, const MatrixX4iRow& T, const std::vector<char>& movable,
                                   const LevelSetRelaxOptions& o) {
  if (static_cast<Eigen::Index>(movable.size()) != V.rows())
    throw Error("relax_level_set: one movable flag per vertex needed");
  if (T.size() > 0 && (T.minCoeff() < 0 || T.maxCoeff() >= V.rows()))
    throw Error("relax_level_set: a tetrahedron's vertex index is out of range");
  if (!(o.radius > 0) || !(o.time_scale > 0)) throw Error("relax_level_set: the radius and time scale must be positive");
  LevelSetRelaxStats st;
  const int nv = static_cast<int>(V.rows());
  std::vector<int> ids, slot(nv, -1);
  for (int v = 0; v < nv; ++v)
    if (movable[v]) slot[v] = static_cast<int>(ids.size()), ids.push_back(v);
  const int n = static_cast<int>(ids.size());
  if (n == 0 || o.rounds <= 0) return st;
  const Rows tets = vertex_tets(T, nv);
  const Rows nb = neighbours(T, tets);
  std::vector<int> touched;  // tetrahedra with a movable corner
  {
    std::vector<char> has(T.rows(), 0);
    parallel_for(static_cast<int>(T.rows()), 0, [&](int t) {
      for (int c = 0; c < 4; ++c) has[t] |= movable[T(t, c)];
    });
    for (Eigen::Index t = 0; t < T.rows(); ++t)
      if (has[t]) touched.push_back(static_cast<int>(t));
  }

  const double r2 = o.radius * o.radius;
  std::vector<Eigen::Vector4d> before;
  reserve_huge(before, T.rows());
  before.resize(T.rows());
  std::vector<double> share(nv);
  for (int round = 0; round < o.rounds; ++round) {
    parallel_for(static_cast<int>(T.rows()), 0, [&](int t) { before[t] = normal4(V, T.row(t).data(), o.time_scale); });
    parallel_for(nv, 0, [&](int v) {  // in tetrahedron order, as a loop over them would add
      double sum = 0;
      for (int k = tets.begin[v]; k < tets.begin[v + 1]; ++k) sum += before[tets.items[k]].norm();
      share[v] = sum;
    });

    // Part of the way to the hyperplane fitted around each vertex, along its spatial normal.
    Eigen::MatrixXd X(n, 3), Y(n, 3);
    std::vector<char> state(n, 0);  // 0 stays, 1 moves, 2 moves half way, 3 undone
    const long long base = epoch.fetch_add(n);
    parallel_for(n, 0, [&](int i) {
      const int v = ids[i];
      X.row(i) = Y.row(i) = V.row(v).head<3>();
      std::vector<long long>& stamp = thread_stamps(nv);
      thread_local std::vector<int> ring;
      const long long mark = base + i;
      ring.assign(1, v);
      stamp[v] = mark;
      // The vertex, its neighbours, and theirs where the neighbour lies well inside the radius (a
      // wider ring costs more than it changes).
      for (size_t r = 0, ring1 = 1; r < ring1; ++r) {
        if (r > 0) {
          Eigen::Vector4d d = (V.row(ring[r]) - V.row(v)).transpose();
          d[3] *= o.time_scale;
          if (d.squaredNorm() > 0.5 * r2) continue;
        }
        for (int k = nb.begin[ring[r]]; k < nb.begin[ring[r] + 1]; ++k)
          if (stamp[nb.items[k]] != mark) stamp[nb.items[k]] = mark, ring.push_back(nb.items[k]);
        if (r == 0) ring1 = ring.size();
      }
      double wsum = 0;
      Eigen::Vector4d c = Eigen::Vector4d::Zero();
      Eigen::Matrix4d C = Eigen::Matrix4d::Zero();
      int count = 0;
      for (int q : ring) {
        Eigen::Vector4d d = (V.row(q) - V.row(v)).transpose();
        d[3] *= o.time_scale;
        const double d2 = d.squaredNorm();
        if (d2 > r2) continue;
        const double w = share[q] * (1 - d2 / r2) * (1 - d2 / r2);
        c += w * d, C += w * d * d.transpose(), wsum += w, ++count;
      }
      if (count < 5 || !(wsum > 0)) return;
      c /= wsum;
      C = C / wsum - c * c.transpose();
      // The smallest eigenvector by inverse iteration from the incident tetrahedra's normal.
      Eigen::Vector4d normal = Eigen::Vector4d::Zero();
      for (int k = tets.begin[v]; k < tets.begin[v + 1]; ++k) normal += before[tets.items[k]];
      const Eigen::LDLT<Eigen::Matrix4d> f(C + 1e-12 * C.trace() * Eigen::Matrix4d::Identity());
      for (int it = 0; it < 3; ++it) normal = f.solve(normal).normalized();
      if (!normal.allFinite()) return;
      const Eigen::Vector3d a = normal.head<3>();
      if (!(a.squaredNorm() > 0.01)) return;  // nearly constant in time: a spatial move would be long
      const Eigen::Vector3d dx = o.weight * c.dot(normal) / a.squaredNorm() * a;
      if (!dx.allFinite() || (o.max_move > 0 && dx.norm() > o.max_move)) return;
      Y.row(i) += dx.transpose();
      state[i] = 1;
    });

    // Undo moves that turn a tetrahedron over: halve first, then give up. Each pass checks the
    // tetrahedra around the vertices the last one changed.
    MatrixX4dRow W(V.rows(), 4);
    advise_huge_pages(W.data(), sizeof(double) * W.size());
    W = V;
    auto place = [&](int i) {
      if (state[i] == 1) W.row(ids[i]).head<3>() = Y.row(i);
      else if (state[i] == 2) W.row(ids[i]).head<3>() = 0.5 * (X.row(i) + Y.row(i));
      else W.row(ids[i]).head<3>() = X.row(i);
    };
    for (int i = 0; i < n; ++i) place(i);
    std::vector<int> check = touched;
    std::vector<char> queued(T.rows(), 0);
    while (!check.empty()) {
      std::vector<char> bad(check.size(), 0);
      parallel_for(static_cast<int>(check.size()), 0,
                   [&](int k) { bad[k] = turned(before[check[k]], normal4(W, T.row(check[k]).data(), o.time_scale)); });
      std::vector<int> changed;
      for (size_t k = 0; k < check.size(); ++k) {
        if (!bad[k]) continue;
        for (int c = 0; c < 4; ++c) {
          const int i = slot[T(check[k], c)];
          if (i < 0 || state[i] == 0 || state[i] == 3) continue;
          state[i] = state[i] == 1 ? 2 : 3;
          place(i);
          changed.push_back(i);
        }
      }
      check.clear();
      for (int i : changed)
        for (int k = tets.begin[ids[i]]; k < tets.begin[ids[i] + 1]; ++k)
          if (!queued[tets.items[k]]) queued[tets.items[k]] = 1, check.push_back(tets.items[k]);
      for (int t : check) queued[t] = 0;
    }
    for (int i = 0; i < n; ++i) {
      st.moved += state[i] == 1 || state[i] == 2;
      st.undone += state[i] == 3;
    }
    V.swap(W);
  }
  return st;
}

}  // namespace dfm
