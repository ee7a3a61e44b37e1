#include "core/anim/iso_manifold.h"

#include <array>
#include <memory>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include <Eigen/LU>

#include "core/bind/parallel_for.h"
#include "core/util/error.h"
#include "core/util/huge_pages.h"

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
    reserve_huge(slots_, n);
    slots_.assign(n, {kEmpty, 0});
    mask_ = n - 1;
  }
  // Room for `more` keys beyond those it holds without growing on the way.
  void expect(size_t more) {
    while (2 * (size_ + more) > slots_.size()) grow();
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
    std::vector<std::pair<std::uint64_t, int>> old;
    reserve_huge(old, 2 * slots_.size());
    old.assign(2 * slots_.size(), {kEmpty, 0});
    old.swap(slots_);
    mask_ = slots_.size() - 1;
    size_ = 0;
    for (const auto& [k, v] : old)
      if (k != kEmpty) emplace(k, v);
  }
  std::vector<std::pair<std::uint64_t, int>> slots_;
  size_t mask_ = 0, size_ = 0;
};

// A slot of a cut simplex: the crossing on the edge from corner a (negative) to corner b (positive).
struct Slot {
  int a = 0, b = 0;
};

// The barycentric coordinates of a slot's crossing in its simplex (corner points s, field f).
Eigen::Matrix<double, 5, 1> slot_weights(const IsoField& f, const int* s, Slot q) {
  const int pa = s[q.a], pb = s[q.b];
  const double la = f.values[pa] / (f.values[pa] - f.values[pb]);  // in (0, 1)
  Eigen::Matrix<double, 5, 1> w = Eigen::Matrix<double, 5, 1>::Zero();
  w[q.a] = 1 - la;
  w[q.b] = la;
  return w;
}

}  // namespace

// The crossings and tetrahedra of the cut simplices, in simplex order. Only the numbering of the
// crossings (first come, first numbered) is sequential: the tetrahedra's orientations and the
// crossings' positions are found in parallel.
struct IsoManifoldBuilder::Impl {
  Impl() : edges_(1 << 16), anchors_(1024) {}

  void add(const IsoField& f, const MatrixX5iRow& D) {
    check(f);
    f_ = &f;
    // The cut simplices and their orientations first, in parallel (each needs only its own corners).
    std::vector<signed char> orientation(static_cast<size_t>(D.rows()), 0);
    parallel_for(static_cast<int>(D.rows()), 0, [&](int s) {
      const int* c = D.row(s).data();
      bool mixed = false;
      for (int j = 1; j < 5; ++j) mixed = mixed || ((f.values[c[j]] < 0) != (f.values[c[0]] < 0));
      if (!mixed) return;
      Eigen::Matrix<double, 5, 4, Eigen::RowMajor> Q;
      for (int j = 0; j < 5; ++j) Q.row(j) = f.points.row(c[j]);
      orientation[static_cast<size_t>(s)] = static_cast<signed char>(orientation_4d(Q));
    });
    size_t cut = 0;
    for (signed char o : orientation) cut += o != 0;
    edges_.expect(cut);
    const size_t first = tets_.size();
    if (tets_.capacity() < first + 2 * cut) {
      std::vector<Candidate> more;
      reserve_huge(more, first + 2 * cut);
      more = tets_;
      tets_.swap(more);
    }
    for (int s = 0; s < D.rows(); ++s)
      if (orientation[static_cast<size_t>(s)] != 0) simplex(s, D.row(s).data());
    const int n = static_cast<int>(tets_.size() - first);
    signs_.resize(tets_.size());
    parallel_for(n, 0, [&](int i) {
      const Candidate& c = tets_[first + i];
      signs_[first + i] = static_cast<signed char>(orient(c, D.row(c.simplex).data(), orientation[static_cast<size_t>(c.simplex)]));
    });
  }

  IsoManifold finish(const IsoField& f) {
    check(f);
    IsoManifold M;
    Eigen::Index kept = 0;
    for (signed char g : signs_) kept += g != 0;
    M.T.resize(kept, 4);
    advise_huge_pages(M.T.data(), sizeof(int) * M.T.size());
    for (size_t i = 0, r = 0; i < tets_.size(); ++i) {
      if (signs_[i] == 0) continue;
      const auto& t = tets_[i].t;
      M.T.row(static_cast<Eigen::Index>(r++)) << t[0], t[1], signs_[i] > 0 ? t[2] : t[3], signs_[i] > 0 ? t[3] : t[2];
    }
    M.V.resize(static_cast<Eigen::Index>(keys_.size()), 4);
    advise_huge_pages(M.V.data(), sizeof(double) * M.V.size());
    parallel_for(static_cast<int>(keys_.size()), 0, [&](int v) { M.V.row(v) = position(f, keys_[v]); });
    return M;
  }

 private:
  static void check(const IsoField& f) {
    const Eigen::Index n = f.points.rows();
    if (f.values.size() != n || static_cast<Eigen::Index>(f.anchored.size()) != n)
      throw Error("iso_manifold: points, values and anchors disagree in size");
    for (Eigen::Index p = 0; p < n; ++p)
      if (!std::isfinite(f.values[p]) || f.values[p] == 0)
        throw Error("iso_manifold: the field at point " + std::to_string(p) + " is zero or not finite");
  }

  // Cuts one 4-simplex (number `simplex` of its part, point indices s[0..4]).
  void simplex(int simplex, const int* s) {
    int neg[5], pos[5], nn = 0, np = 0;
    for (int j = 0; j < 5; ++j) (f_->values[s[j]] < 0 ? neg[nn++] : pos[np++]) = j;
    if (nn == 0 || np == 0) return;
    s_ = s;
    simplex_ = simplex;
    nslots_ = 0;
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

  // A tetrahedron of four slots of a simplex, its corners' crossing numbers in t.
  struct Candidate {
    std::array<int, 4> t;
    int simplex;
    std::uint32_t slots;  // slot k's corners a, b at bits 6k and 6k + 3
    Slot slot(int k) const { return {static_cast<int>(slots >> (6 * k) & 7), static_cast<int>(slots >> (6 * k + 3) & 7)}; }
  };

  // The crossing of slot (a, b) of the current simplex: its number, and its slot (at most 6 per
  // simplex).
  int crossing(int a, int b) {
    const int pa = s_[a], pb = s_[b];
    const bool anchored = f_->anchored[pa];
    const std::uint64_t key = anchored ? static_cast<std::uint64_t>(pa) : static_cast<std::uint64_t>(pa) << 32 | static_cast<std::uint32_t>(pb);
    const auto [v, fresh] = (anchored ? anchors_ : edges_).emplace(key, static_cast<int>(keys_.size()));
    if (fresh) keys_.push_back(anchored ? Key{pa, -1} : Key{pa, pb});
    slots_[nslots_] = {a, b};
    id_[nslots_] = v;
    return nslots_++;
  }

  void tet(int a, int b, int c, int d) {
    const std::array<int, 4> t = {id_[a], id_[b], id_[c], id_[d]};
    if (t[0] == t[1] || t[0] == t[2] || t[0] == t[3] || t[1] == t[2] || t[1] == t[3] || t[2] == t[3]) return;
    std::uint32_t packed = 0;
    const int q[4] = {a, b, c, d};
    for (int k = 0; k < 4; ++k) packed |= static_cast<std::uint32_t>(slots_[q[k]].a | slots_[q[k]].b << 3) << (6 * k);
    tets_.push_back({t, simplex_, packed});
  }

  // +1 when the candidate's 4D normal points toward its simplex's positive corners (simplex s of
  // orientation o) as it stands, -1 when its last two corners must swap, 0 when it is
  // flat: the sign of det[q1 - q0, c - q0, ...] is the determinant of the barycentric rows times the
  // simplex's orientation, and barycentric rows stay well scaled where the simplex is a sliver. The
  // rows are the unanchored crossings': the level set there is a proper convex polytope, and an
  // anchored crossing only moves a corner onto its point (which may flatten the piece, never turn it
  // over).
  int orient(const Candidate& c, const int* s, int o) const {
    Eigen::Matrix<double, 5, 1> positive_centroid = Eigen::Matrix<double, 5, 1>::Zero();
    int np = 0;
    for (int j = 0; j < 5; ++j) np += f_->values[s[j]] >= 0;
    for (int j = 0; j < 5; ++j)
      if (f_->values[s[j]] >= 0) positive_centroid[j] = 1.0 / np;
    Eigen::Matrix<double, 5, 5> B;
    B.row(0) = slot_weights(*f_, s, c.slot(0)).transpose();
    B.row(1) = positive_centroid.transpose();
    B.row(2) = slot_weights(*f_, s, c.slot(1)).transpose();
    B.row(3) = slot_weights(*f_, s, c.slot(2)).transpose();
    B.row(4) = slot_weights(*f_, s, c.slot(3)).transpose();
    const double det = B.determinant() * o;
    return det < 0 ? -1 : det == 0 ? 0 : 1;
  }

  // A crossing: the edge from point a (negative) to point b (positive), or the anchored point a
  // itself (b = -1).
  struct Key {
    int a, b;
  };
  static Eigen::RowVector4d position(const IsoField& f, Key k) {
    if (k.b < 0) return f.points.row(k.a);
    const double la = f.values[k.a] / (f.values[k.a] - f.values[k.b]);
    Eigen::RowVector4d x = (1 - la) * f.points.row(k.a) + la * f.points.row(k.b);
    if (f.points(k.a, 3) == f.points(k.b, 3)) x[3] = f.points(k.a, 3);  // a layer's crossing stays in its layer
    return x;
  }

  const IsoField* f_ = nullptr;
  const int* s_ = nullptr;
  int simplex_ = 0;
  Slot slots_[6];
  int id_[6] = {0, 0, 0, 0, 0, 0};
  int nslots_ = 0;
  KeyIndex edges_, anchors_;
  std::vector<Key> keys_;
  std::vector<Candidate> tets_;
  std::vector<signed char> signs_;  // per candidate: +1 as it stands, -1 swapped, 0 dropped
};

IsoManifoldBuilder::IsoManifoldBuilder() : impl_(std::make_unique<Impl>()) {}
IsoManifoldBuilder::~IsoManifoldBuilder() = default;
void IsoManifoldBuilder::add(const IsoField& field, const MatrixX5iRow& simplices) { impl_->add(field, simplices); }
IsoManifold IsoManifoldBuilder::finish(const IsoField& field) { return impl_->finish(field); }

IsoManifold iso_manifold(const IsoField& f, const Delaunay4& D) {
  IsoManifoldBuilder b;
  b.add(f, D.simplices);
  return b.finish(f);
}

}  // namespace dfm
