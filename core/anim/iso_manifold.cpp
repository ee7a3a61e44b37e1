#include "core/anim/iso_manifold.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include <Eigen/LU>

#include "core/bind/parallel_for.h"
#include "core/util/error.h"

namespace dfm {

namespace {

// Vertex permutations of a prism (0 1 2 below, 3 4 5 above, i over i + 3) that bring corner i to 0.
constexpr int kRotate[6][6] = {{0, 1, 2, 3, 4, 5}, {1, 2, 0, 4, 5, 3}, {2, 0, 1, 5, 3, 4},
                               {3, 5, 4, 0, 2, 1}, {4, 3, 5, 1, 0, 2}, {5, 4, 3, 2, 1, 0}};

// Crossing keys to vertex numbers: open addressing, linear probing, never erased. (The crossings of
// a manifold of millions of tetrahedra: std::unordered_map's node per key made this the costly part.)
class KeyIndex {
 public:
  explicit KeyIndex(size_t expected) {
    size_t n = 16;
    while (n < 2 * expected) n *= 2;
    slots_.assign(n, {kEmpty, 0});
    mask_ = n - 1;
  }
  // The value for key, inserting `value` if absent; whether it was inserted.
  std::pair<int, bool> emplace(std::uint64_t key, int value) {
    if (2 * (size_ + 1) > slots_.size()) grow();
    for (size_t i = (key * 0x9E3779B97F4A7C15ull) >> 20 & mask_;; i = (i + 1) & mask_) {
      if (slots_[i].first == key) return {slots_[i].second, false};
      if (slots_[i].first == kEmpty) {
        slots_[i] = {key, value};
        ++size_;
        return {value, true};
      }
    }
  }

 private:
  static constexpr std::uint64_t kEmpty = ~0ull;
  void grow() {
    std::vector<std::pair<std::uint64_t, int>> old(2 * slots_.size(), {kEmpty, 0});
    old.swap(slots_);
    mask_ = slots_.size() - 1;
    size_ = 0;
    for (const auto& [k, v] : old)
      if (k != kEmpty) emplace(k, v);
  }
  std::vector<std::pair<std::uint64_t, int>> slots_;
  size_t mask_ = 0, size_ = 0;
};

class Writer {
 public:
  Writer(const IsoField& f, size_t cut) : f_(f), edges_(cut), anchors_(1024) {
    T_.reserve(2 * cut);
    V_.reserve(cut / 4);
  }

  // Cuts one 4-simplex (point indices s[0..4], orientation o = +-1).
  void simplex(const int* s, int o) {
    int neg[5], pos[5], nn = 0, np = 0;
    for (int j = 0; j < 5; ++j) (f_.values[s[j]] < 0 ? neg[nn++] : pos[np++]) = j;
    if (nn == 0 || np == 0) return;
    s_ = s;
    o_ = o;
    nslots_ = 0;
    positive_centroid_.setZero();
    for (int k = 0; k < np; ++k) positive_centroid_[pos[k]] = 1.0 / np;
    if (nn == 1 || np == 1) {
      int q[4];
      for (int k = 0; k < 4; ++k) q[k] = nn == 1 ? crossing(neg[0], pos[k]) : crossing(neg[k], pos[0]);
      tet(q[0], q[1], q[2], q[3]);
      return;
    }
    // A prism: triangles A (first of the pair side) and B, A[i] over B[i].
    int c[6];
    for (int i = 0; i < 3; ++i) {
      c[i] = nn == 2 ? crossing(neg[0], pos[i]) : crossing(neg[i], pos[0]);
      c[i + 3] = nn == 2 ? crossing(neg[1], pos[i]) : crossing(neg[i], pos[1]);
    }
    int m = 0;
    for (int i = 1; i < 6; ++i)
      if (id_[c[i]] < id_[c[m]]) m = i;
    int I[6];
    for (int i = 0; i < 6; ++i) I[i] = c[kRotate[m][i]];
    auto id = [&](int k) { return id_[I[k]]; };
    if (std::min(id(1), id(5)) < std::min(id(2), id(4))) {
      tet(I[0], I[1], I[2], I[5]);
      tet(I[0], I[1], I[5], I[4]);
    } else {
      tet(I[0], I[1], I[2], I[4]);
      tet(I[0], I[4], I[2], I[5]);
    }
    tet(I[0], I[4], I[5], I[3]);
  }

  IsoManifold result() {
    IsoManifold M;
    const auto nv = static_cast<Eigen::Index>(V_.size()), nt = static_cast<Eigen::Index>(T_.size());
    M.V = Eigen::Map<const MatrixX4dRow>(V_.empty() ? nullptr : V_.front().data(), nv, 4);
    M.T = Eigen::Map<const MatrixX4iRow>(T_.empty() ? nullptr : T_.front().data(), nt, 4);
    return M;
  }

 private:
  // The crossing on the edge between corners a (negative) and b (positive) of the current simplex:
  // a slot (at most 6 per simplex) holding its global vertex and its barycentric coordinates.
  int crossing(int a, int b) {
    const int pa = s_[a], pb = s_[b];
    const double la = f_.values[pa] / (f_.values[pa] - f_.values[pb]);  // in (0, 1)
    Eigen::Matrix<double, 5, 1> w = Eigen::Matrix<double, 5, 1>::Zero();
    w[a] = 1 - la;
    w[b] = la;
    int v;
    if (f_.anchored[pa]) {
      v = vertex_of(anchors_, static_cast<std::uint64_t>(pa), [&] { return f_.points.row(pa).eval(); });
    } else {
      const std::uint64_t key = static_cast<std::uint64_t>(pa) << 32 | static_cast<std::uint32_t>(pb);
      v = vertex_of(edges_, key, [&] {
        Eigen::RowVector4d x = (1 - la) * f_.points.row(pa) + la * f_.points.row(pb);
        if (f_.points(pa, 3) == f_.points(pb, 3)) x[3] = f_.points(pa, 3);  // a layer's crossing stays in its layer
        return x;
      });
    }
    slots_[nslots_] = {v, w};
    id_[nslots_] = v;
    return nslots_++;
  }

  template <class Make>
  int vertex_of(KeyIndex& map, std::uint64_t key, const Make& make) {
    const auto [v, fresh] = map.emplace(key, static_cast<int>(V_.size()));
    if (fresh) V_.push_back(make());
    return v;
  }

  // A tetrahedron of slots, oriented so that its 4D normal points toward the positive corners: the
  // sign of det[q1 - q0, c - q0, ...] is the determinant of the barycentric rows times the simplex's
  // orientation, and barycentric rows stay well scaled where the simplex is a sliver. The rows are
  // the unanchored crossings': the level set there is a proper convex polytope, and an anchored
  // crossing only moves a corner onto its point (which may flatten the piece, never turn it over).
  void tet(int a, int b, int c, int d) {
    std::array<int, 4> t = {id_[a], id_[b], id_[c], id_[d]};
    if (t[0] == t[1] || t[0] == t[2] || t[0] == t[3] || t[1] == t[2] || t[1] == t[3] || t[2] == t[3]) return;
    Eigen::Matrix<double, 5, 5> B;
    B.row(0) = slots_[a].second.transpose();
    B.row(1) = positive_centroid_.transpose();
    B.row(2) = slots_[b].second.transpose();
    B.row(3) = slots_[c].second.transpose();
    B.row(4) = slots_[d].second.transpose();
    const double det = B.determinant() * o_;
    if (det == 0) return;
    if (det < 0) std::swap(t[2], t[3]);
    T_.push_back(t);
  }

  const IsoField& f_;
  const int* s_ = nullptr;
  int o_ = 1;
  Eigen::Matrix<double, 5, 1> positive_centroid_;
  std::pair<int, Eigen::Matrix<double, 5, 1>> slots_[6];
  int id_[6] = {0, 0, 0, 0, 0, 0};
  int nslots_ = 0;
  KeyIndex edges_, anchors_;
  std::vector<Eigen::RowVector4d> V_;
  std::vector<std::array<int, 4>> T_;
};

}  // namespace

IsoManifold iso_manifold(const IsoField& f, const Delaunay4& D) {
  const Eigen::Index n = f.points.rows();
  if (f.values.size() != n || static_cast<Eigen::Index>(f.anchored.size()) != n)
    throw Error("iso_manifold: points, values and anchors disagree in size");
  for (Eigen::Index p = 0; p < n; ++p)
    if (!std::isfinite(f.values[p]) || f.values[p] == 0)
      throw Error("iso_manifold: the field at point " + std::to_string(p) + " is zero or not finite");
  // The cut simplices and their orientations first, in parallel (each needs only its own corners).
  std::vector<signed char> orientation(static_cast<size_t>(D.simplices.rows()), 0);
  parallel_for(static_cast<int>(D.simplices.rows()), 0, [&](int s) {
    const int* c = D.simplices.row(s).data();
    bool mixed = false;
    for (int j = 1; j < 5; ++j) mixed = mixed || ((f.values[c[j]] < 0) != (f.values[c[0]] < 0));
    if (!mixed) return;
    Eigen::Matrix<double, 5, 4, Eigen::RowMajor> Q;
    for (int j = 0; j < 5; ++j) Q.row(j) = f.points.row(c[j]);
    orientation[static_cast<size_t>(s)] = static_cast<signed char>(orientation_4d(Q));
  });
  size_t cut = 0;
  for (signed char o : orientation) cut += o != 0;
  Writer w(f, cut);
  for (int s = 0; s < D.simplices.rows(); ++s)
    if (orientation[static_cast<size_t>(s)] != 0) w.simplex(D.simplices.row(s).data(), orientation[static_cast<size_t>(s)]);
  return w.result();
}

}  // namespace dfm
