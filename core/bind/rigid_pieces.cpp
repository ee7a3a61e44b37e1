#include "core/bind/rigid_pieces.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "core/bind/robust_volume.h"
#include "core/util/error.h"

namespace dfm {
namespace {

// The vertex of `among` nearest to x.
int nearest(const Eigen::MatrixXd& V, const std::vector<int>& among, const Eigen::RowVector3d& x) {
  int best = among.front();
  double bd = 1e300;
  for (int v : among) {
    const double d = (V.row(v) - x).squaredNorm();
    if (d < bd) bd = d, best = v;
  }
  return best;
}

// The handled vertex nearest to the piece: from the piece's centroid, alternating nearest-vertex steps
// between the piece and the handled vertices (exact for convex pieces; O(#V) per step).
int anchor_of(const Eigen::MatrixXd& V, const std::vector<int>& piece, const std::vector<int>& handled) {
  Eigen::RowVector3d c = Eigen::RowVector3d::Zero();
  for (int v : piece) c += V.row(v);
  int h = nearest(V, handled, c / static_cast<double>(piece.size()));
  for (int round = 0; round < 3; ++round) {
    const int q = nearest(V, piece, V.row(h));
    const int next = nearest(V, handled, V.row(q));
    if (next == h) break;
    h = next;
  }
  return h;
}

// User vertices per piece: a user vertex belongs to the tet vertex with its largest coefficient.
std::vector<int> user_vertices_per_piece(const Eigen::SparseMatrix<double>& to_user, const Eigen::VectorXi& comp,
                                         int pieces) {
  std::vector<int> best(to_user.rows(), -1);
  std::vector<double> best_w(to_user.rows(), -1);
  for (int k = 0; k < to_user.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(to_user, k); it; ++it)
      if (it.value() > best_w[it.row()]) best_w[it.row()] = it.value(), best[it.row()] = static_cast<int>(it.col());
  std::vector<int> n(pieces, 0);
  for (int t : best)
    if (t >= 0 && t < comp.size() && comp(t) >= 0) ++n[comp(t)];
  return n;
}

std::string describe(const std::vector<RigidPiece>& rigid, int pieces) {
  std::string s = std::to_string(rigid.size()) + " of " + std::to_string(pieces) +
                  " pieces of the volume have no handle; each moves rigidly with the nearest handled piece: ";
  const size_t shown = std::min<size_t>(rigid.size(), 12);
  for (size_t i = 0; i < shown; ++i)
    s += (i ? ", piece " : "piece ") + std::to_string(rigid[i].piece) + " (" + std::to_string(rigid[i].vertices) +
         " vertices)";
  if (shown < rigid.size()) s += " and " + std::to_string(rigid.size() - shown) + " more";
  return s;
}

// Merges extra rows into (b, bc), keeping b sorted.
void add_rows(BindVolume& vol, const std::vector<std::pair<int, Eigen::RowVectorXd>>& extra) {
  std::vector<std::pair<int, Eigen::RowVectorXd>> all;
  for (int i = 0; i < vol.b.size(); ++i) all.push_back({vol.b(i), vol.bc.row(i)});
  all.insert(all.end(), extra.begin(), extra.end());
  std::sort(all.begin(), all.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  const Eigen::Index nh = vol.bc.cols();
  vol.b.resize(all.size());
  vol.bc.resize(all.size(), nh);
  for (size_t i = 0; i < all.size(); ++i) vol.b(i) = all[i].first, vol.bc.row(i) = all[i].second;
}

}  // namespace

void attach_free_pieces(BindVolume& vol) {
  vol.rigid_pieces.clear();
  if (vol.b.size() == 0) return;
  Eigen::VectorXi comp;
  const int nc = tet_vertex_components(vol.tets, comp);
  if (nc <= 1) return;
  std::vector<char> handled(nc, 0);
  for (int i = 0; i < vol.b.size(); ++i) handled[comp(vol.b(i))] = 1;
  std::vector<std::vector<int>> members(nc);
  std::vector<int> handled_vertices;
  for (int v = 0; v < comp.size(); ++v)
    if (comp(v) >= 0) (handled[comp(v)] ? handled_vertices : members[comp(v)]).push_back(v);
  const std::vector<int> user_count = user_vertices_per_piece(vol.to_user, comp, nc);
  std::vector<int> constrained(vol.b.data(), vol.b.data() + vol.b.size());
  std::vector<int> row_of(vol.tets.V.rows(), -1);
  for (int i = 0; i < vol.b.size(); ++i) row_of[vol.b(i)] = i;
  std::vector<std::pair<int, Eigen::RowVectorXd>> extra;
  for (int c = 0; c < nc; ++c) {
    if (handled[c]) continue;
    RigidPiece p;
    p.piece = c;
    p.vertices = user_count[c];
    p.anchor = anchor_of(vol.tets.V, members[c], handled_vertices);
    p.tet_vertices = members[c];
    // Until the solve gives the anchor's weights: the row of the constrained vertex nearest to it.
    const Eigen::RowVectorXd row = vol.bc.row(row_of[nearest(vol.tets.V, constrained, vol.tets.V.row(p.anchor))]);
    for (int v : members[c]) extra.push_back({v, row});
    vol.rigid_pieces.push_back(std::move(p));
  }
  if (vol.rigid_pieces.empty()) return;
  add_rows(vol, extra);
  vol.notes.push_back(describe(vol.rigid_pieces, nc));
}

void apply_rigid_pieces(const BindVolume& vol, Eigen::MatrixXd& W) {
  for (const RigidPiece& p : vol.rigid_pieces) {
    if (p.anchor < 0 || p.anchor >= W.rows()) throw Error("bind volume: a rigid piece's anchor is out of range");
    const Eigen::RowVectorXd row = W.row(p.anchor);
    for (int v : p.tet_vertices) {
      if (v < 0 || v >= W.rows()) throw Error("bind volume: a rigid piece's vertex is out of range");
      W.row(v) = row;
    }
  }
}

}  // namespace dfm
