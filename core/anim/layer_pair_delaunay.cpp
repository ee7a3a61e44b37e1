#include "core/anim/layer_pair_delaunay.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include <CGAL/Exact_rational.h>
#include <CGAL/Interval_nt.h>

#include "core/mesh/mesh_info.h"
#include "core/util/error.h"

namespace dfm {

namespace {

using Q = CGAL::Exact_rational;
using I = CGAL::Interval_nt<false>;  // inside a CGAL::Protect_FPU_rounding scope only

template <class N>
struct P3 {
  N x, y, z;
};
template <class N>
P3<N> operator-(const P3<N>& a, const P3<N>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class N>
P3<N> operator+(const P3<N>& a, const P3<N>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class N>
P3<N> operator*(const N& s, const P3<N>& a) {
  return {s * a.x, s * a.y, s * a.z};
}
template <class N>
N dot(const P3<N>& a, const P3<N>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class N>
P3<N> cross(const P3<N>& a, const P3<N>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class N>
P3<N> row(const Eigen::MatrixXd& X, int i) {
  return {N(X(i, 0)), N(X(i, 1)), N(X(i, 2))};
}

// The circumcentre of tetrahedron abcd (its Voronoi vertex).
template <class N>
P3<N> circumcentre(const P3<N>& a, const P3<N>& b, const P3<N>& c, const P3<N>& d) {
  const P3<N> u = b - a, v = c - a, w = d - a;
  const N den = N(2) * dot(u, cross(v, w));
  const P3<N> num = dot(u, u) * cross(v, w) + dot(v, v) * cross(w, u) + dot(w, w) * cross(u, v);
  return {a.x + num.x / den, a.y + num.y / den, a.z + num.z / den};
}

// |c - r|^2 - |c - q|^2: negative when r is nearer c than q.
template <class N>
N farther(const P3<N>& c, const P3<N>& q, const P3<N>& r) {
  return dot(r - q, r + q - N(2) * c);
}

// Bounds of double evaluations: a value and how far the exact one may lie from it.
struct Bounded {
  double v, e;
};
constexpr double kRound = 16 * std::numeric_limits<double>::epsilon();

double abs_dot(const P3<double>& a, const P3<double>& b) {
  return std::abs(a.x) * std::abs(b.x) + std::abs(a.y) * std::abs(b.y) + std::abs(a.z) * std::abs(b.z);
}
P3<double> abs3(const P3<double>& a) { return {std::abs(a.x), std::abs(a.y), std::abs(a.z)}; }
double l1(const P3<double>& a) { return std::abs(a.x) + std::abs(a.y) + std::abs(a.z); }

// farther(c, q, r) in doubles, c known within e in each coordinate.
Bounded farther_bounded(const P3<double>& c, double e, const P3<double>& q, const P3<double>& r) {
  const P3<double> d = r - q;
  const P3<double> m = abs3(r) + abs3(q) + 2.0 * abs3(c);
  return {farther(c, q, r), 2 * e * l1(d) + kRound * abs_dot(d, m)};
}

int sign_of(const Bounded& b) {
  if (b.v > b.e) return 1;
  if (b.v < -b.e) return -1;
  return 0;  // uncertain
}

struct Tie {};  // an exact tie: the triangulation is not unique

// One layer's simplices against the other's Voronoi diagram (the header's (4,1) and (3,2)); A's
// points numbered from a0, B's from b0.
class HalfOverlay {
 public:
  HalfOverlay(const DelaunayLayer& a, const DelaunayLayer& b)
      : A_(a), B_(b), adj_(vertex_neighbours(b.tets, static_cast<int>(b.points.rows()))) {
    points();
    centres();
  }

  // Per A tetrahedron, the B point nearest its circumcentre.
  void nearest() {
    const Eigen::MatrixXi& T = A_.tets;
    const Eigen::MatrixXi& N = A_.neighbours;
    const int nt = static_cast<int>(T.rows());
    near_.assign(nt, -1);
    std::vector<int> queue;
    for (int seed = 0; seed < nt; ++seed) {
      if (near_[seed] >= 0) continue;
      near_[seed] = walk_to_nearest(seed, brute_nearest(c_[seed]));
      queue.assign(1, seed);
      for (size_t k = 0; k < queue.size(); ++k) {
        const int t = queue[k];
        for (int j = 0; j < 4; ++j) {
          const int u = N(t, j);
          if (u < 0 || near_[u] >= 0) continue;
          near_[u] = walk_to_nearest(u, near_[t]);
          queue.push_back(u);
        }
      }
    }
  }

  // The (4,1) and (3,2) simplices, A's points numbered from a0 and B's from b0.
  void emit(int a0, int b0, std::vector<Eigen::Matrix<int, 1, 5>>& out) {
    const Eigen::MatrixXi& T = A_.tets;
    const Eigen::MatrixXi& N = A_.neighbours;
    for (int t = 0; t < T.rows(); ++t)
      out.push_back((Eigen::Matrix<int, 1, 5>() << a0 + T(t, 0), a0 + T(t, 1), a0 + T(t, 2), a0 + T(t, 3), b0 + near_[t]).finished());
    for (int t = 0; t < T.rows(); ++t)
      for (int j = 0; j < 4; ++j) {
        const int u = N(t, j);
        if (u >= 0 && (u < t || near_[u] == near_[t])) continue;  // once; a segment in one cell crosses nothing
        int tri[3];
        for (int i = 0, k = 0; i < 4; ++i)
          if (i != j) tri[k++] = a0 + T(t, i);
        walk_edge(t, j, [&](int q, int r) { out.push_back((Eigen::Matrix<int, 1, 5>() << tri[0], tri[1], tri[2], b0 + q, b0 + r).finished()); });
      }
  }

 private:
  void points() {
    bp_.resize(B_.points.rows());
    for (size_t v = 0; v < bp_.size(); ++v) bp_[v] = row<double>(B_.points, static_cast<int>(v));
  }

  // Each A tetrahedron's circumcentre in doubles, and how far (per coordinate) the exact one may lie.
  void centres() {
    const Eigen::MatrixXi& T = A_.tets;
    const int nt = static_cast<int>(T.rows());
    c_.resize(nt);
    e_.resize(nt);
    exact_.resize(nt);
    {
      CGAL::Protect_FPU_rounding<true> upward;
      for (int t = 0; t < nt; ++t) {
        const P3<I> c = circumcentre(row<I>(A_.points, T(t, 0)), row<I>(A_.points, T(t, 1)), row<I>(A_.points, T(t, 2)),
                                     row<I>(A_.points, T(t, 3)));
        c_[t] = {c.x.inf() / 2 + c.x.sup() / 2, c.y.inf() / 2 + c.y.sup() / 2, c.z.inf() / 2 + c.z.sup() / 2};
        double e = 0;
        for (const I& x : {c.x, c.y, c.z}) e = std::max(e, x.sup() - x.inf());
        e_[t] = std::isfinite(e) ? e : HUGE_VAL;
        if (!std::isfinite(c_[t].x + c_[t].y + c_[t].z)) c_[t] = {0, 0, 0};
      }
    }
    // Nearly flat tetrahedra (their circumcentres barely known in intervals): exactly, then rounded.
    for (int t = 0; t < nt; ++t) {
      const P3<double> a = row<double>(A_.points, T(t, 0)), b = row<double>(A_.points, T(t, 1));
      if (!(e_[t] > 1e-12 * (l1(b - a) + std::abs(c_[t].x) + std::abs(c_[t].y) + std::abs(c_[t].z)))) continue;
      const P3<Q>& q = exact_centre(t);
      double e = 0;
      double* c[3] = {&c_[t].x, &c_[t].y, &c_[t].z};
      int k = 0;
      for (const Q* x : {&q.x, &q.y, &q.z}) {
        const std::pair<double, double> i = CGAL::to_interval(*x);
        *c[k++] = i.first / 2 + i.second / 2;
        e = std::max(e, i.second - i.first);
      }
      e_[t] = std::isfinite(e) && std::isfinite(c_[t].x + c_[t].y + c_[t].z) ? e : HUGE_VAL;
    }
  }

  const P3<Q>& exact_centre(int t) {
    if (!exact_[t]) {
      const Eigen::MatrixXi& T = A_.tets;
      exact_[t] = circumcentre(row<Q>(A_.points, T(t, 0)), row<Q>(A_.points, T(t, 1)), row<Q>(A_.points, T(t, 2)),
                               row<Q>(A_.points, T(t, 3)));
    }
    return *exact_[t];
  }

  int brute_nearest(const P3<double>& c) const {
    int best = 0;
    double d = HUGE_VAL;
    for (size_t v = 0; v < bp_.size(); ++v) {
      const P3<double> x = bp_[v] - c;
      if (dot(x, x) < d) d = dot(x, x), best = static_cast<int>(v);
    }
    return best;
  }

  // The sign of farther(centre of t, q, r), exact.
  int farther_sign(int t, int q, int r) {
    if (const int s = sign_of(farther_bounded(c_[t], e_[t], bp_[q], bp_[r]))) return s;
    const int s = CGAL::sign(farther(exact_centre(t), row<Q>(B_.points, q), row<Q>(B_.points, r)));
    if (s == 0) throw Tie{};
    return s;
  }

  // Greedy descent on B's Delaunay graph ends at the point nearest t's circumcentre.
  int walk_to_nearest(int t, int q) {
    for (bool moved = true; moved;) {
      moved = false;
      for (size_t k = 0; k < adj_[q].size() && !moved; ++k)
        if (farther_sign(t, q, adj_[q][k]) < 0) q = adj_[q][k], moved = true;
    }
    return q;
  }

  // The Voronoi edge of the face of tet t opposite corner j: from t's circumcentre c1 along d, to the
  // neighbour's circumcentre (d = c2 - c1) or out of the hull (d the face's outward normal). The point
  // c1 + s d leaves q's cell into r's at s = H / G, H = farther(c1, q, r), G = 2 d.(r - q) > 0.
  template <class Cross>
  void walk_edge(int t, int j, const Cross& cross_at) {
    const Eigen::MatrixXi& T = A_.tets;
    const int u = A_.neighbours(t, j);
    int f[3];
    for (int i = 0, k = 0; i < 4; ++i)
      if (i != j) f[k++] = T(t, i);
    // The direction in doubles with its error per coordinate, and exactly on demand.
    P3<double> d;
    double ed;
    std::optional<P3<Q>> dq;
    auto exact_d = [&]() -> const P3<Q>& {
      if (!dq) {
        if (u >= 0) {
          dq = exact_centre(u) - exact_centre(t);
        } else {
          const P3<Q> a = row<Q>(A_.points, f[0]);
          P3<Q> n = cross(row<Q>(A_.points, f[1]) - a, row<Q>(A_.points, f[2]) - a);
          if (CGAL::sign(dot(n, row<Q>(A_.points, T(t, j)) - a)) > 0) n = Q(-1) * n;
          dq = n;
        }
      }
      return *dq;
    };
    if (u >= 0) {
      d = c_[u] - c_[t];
      ed = e_[u] + e_[t] + kRound * std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
    } else {
      const P3<Q>& n = exact_d();
      d = {CGAL::to_double(n.x), CGAL::to_double(n.y), CGAL::to_double(n.z)};
      ed = kRound * std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
    }
    const P3<double>& c1 = c_[t];
    const double e1 = e_[t];
    auto H = [&](int q, int r) { return farther_bounded(c1, e1, bp_[q], bp_[r]); };
    auto G = [&](int q, int r) -> Bounded {
      const P3<double> x = bp_[r] - bp_[q];
      return {2 * dot(d, x), 2 * ed * l1(x) + kRound * abs_dot(d, x) + kRound * l1(x) * l1(d)};
    };
    auto Hq = [&](int q, int r) { return farther(exact_centre(t), row<Q>(B_.points, q), row<Q>(B_.points, r)); };
    auto Gq = [&](int q, int r) { return Q(2) * dot(exact_d(), row<Q>(B_.points, r) - row<Q>(B_.points, q)); };
    auto exact_sign = [&](const Q& v) {
      const int s = CGAL::sign(v);
      if (s == 0) throw Tie{};
      return s;
    };

    int q = near_[t], prev = -1;
    for (int steps = 0;; ++steps) {
      if (steps > static_cast<int>(bp_.size())) throw Error("layer_pair_delaunay: a Voronoi edge walk does not end");
      int best = -1;
      Bounded hb{0, 0}, gb{0, 0};
      auto consider = [&](int r, const Bounded& h, const Bounded& g) {
        if (best < 0) {
          best = r, hb = h, gb = g;
          return;
        }
        // Earlier when h / g < hb / gb.
        const Bounded cmp{h.v * gb.v - hb.v * g.v,
                          std::abs(h.v) * gb.e + std::abs(gb.v) * h.e + std::abs(hb.v) * g.e + std::abs(g.v) * hb.e +
                              h.e * gb.e + hb.e * g.e + kRound * (std::abs(h.v * gb.v) + std::abs(hb.v * g.v))};
        int s = sign_of(cmp);
        if (s == 0) s = exact_sign(Hq(q, r) * Gq(q, best) - Hq(q, best) * Gq(q, r));
        if (s < 0) best = r, hb = h, gb = g;
      };
      int level[16], nlevel = 0;  // nearly parallel to their bisectors: considered last
      for (const int r : adj_[q]) {
        if (r == prev) continue;
        const Bounded g = G(q, r);
        const int gs = sign_of(g);
        if (gs < 0) continue;
        if (gs == 0 && nlevel < 16) level[nlevel++] = r;
        else if (gs == 0 && CGAL::sign(Gq(q, r)) > 0) consider(r, H(q, r), g);
        else consider(r, H(q, r), g);
      }
      for (int i = 0; i < nlevel; ++i) {
        const int r = level[i];
        const Bounded g = G(q, r), h = H(q, r);
        // Crossing at h / g, g in (0, |g.v| + g.e]: after the limit s (the best so far, else the far
        // circumcentre at 1) whatever g is?
        const double gmax = std::abs(g.v) + g.e, hmin = h.v - h.e;
        if (best >= 0 && gb.v - gb.e > 0 && hmin > 0 && hmin * (gb.v - gb.e) > (hb.v + hb.e) * gmax) continue;
        if (best < 0 && u >= 0 && hmin > gmax) continue;
        if (CGAL::sign(Gq(q, r)) > 0) consider(r, h, g);  // 0: parallel to that bisector, never crossing it
      }
      if (best >= 0 && u >= 0) {  // before the far circumcentre (s < 1)?
        int s = sign_of(Bounded{hb.v - gb.v, hb.e + gb.e + kRound * (std::abs(hb.v) + std::abs(gb.v))});
        if (s == 0) s = exact_sign(Hq(q, best) - Gq(q, best));
        if (s > 0) best = -1;
      }
      if (best < 0) break;
      cross_at(q, best);
      prev = q;
      q = best;
    }
    if (u >= 0 && q != near_[u]) throw Error("layer_pair_delaunay: a Voronoi edge walk ends in the wrong cell");
  }

  const DelaunayLayer &A_, &B_;
  std::vector<std::vector<int>> adj_;  // B's Delaunay neighbours
  std::vector<P3<double>> bp_;    // B's points
  std::vector<P3<double>> c_;     // A's circumcentres
  std::vector<double> e_;
  std::vector<std::optional<P3<Q>>> exact_;
  std::vector<int> near_;
};

}  // namespace

std::optional<MatrixX5iRow> layer_pair_delaunay(const DelaunayLayer& a, const DelaunayLayer& b) {
  const int na = static_cast<int>(a.points.rows());
  std::vector<Eigen::Matrix<int, 1, 5>> out;
  try {
    HalfOverlay ab(a, b), ba(b, a);
    ab.nearest();
    ba.nearest();
    ab.emit(0, na, out);
    ba.emit(na, 0, out);
  } catch (const Tie&) {
    return std::nullopt;
  }
  MatrixX5iRow S(static_cast<Eigen::Index>(out.size()), 5);
  for (size_t i = 0; i < out.size(); ++i) S.row(static_cast<Eigen::Index>(i)) = out[i];
  return S;
}

}  // namespace dfm
