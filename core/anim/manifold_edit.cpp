#include "core/anim/manifold_edit.h"

#include <algorithm>
#include <array>
#include <string>
#include <cmath>
#include <unordered_map>

#include <Eigen/Geometry>
#include <Eigen/Sparse>

#include "core/anim/dual_laplacian.h"
#include "core/anim/manifold_edit_volume.h"
#include "core/anim/manifold_retime.h"
#include "core/anim/manifold_laplacian.h"
#include "core/bind/cholesky.h"
#include "core/util/error.h"

namespace dfm {

struct ManifoldEditor::Impl {
  EditRegion sel;
  Eigen::Vector3d pivot;
  ManifoldEditOptions options;
  MatrixX4dRow V;                    // the original vertices
  // Rows of L over manifold vertices: primal, one per region vertex (Eq. 4.1; the vertex first, then its
  // neighbours); dual, one per tetrahedron with a region vertex (dual_laplacian.h). turn: the region
  // slots whose reach, summed and divided by turn_div, is the row's share of the handle's turn (4.2.1).
  struct Row {
    std::vector<int> vertices;
    std::vector<double> coeffs;
    std::vector<int> turn;
    double turn_div = 1;
  };
  std::vector<Row> rows;
  Eigen::MatrixXd delta;             // #rows x 3: original differential coordinates (x, y, z)
  std::vector<std::array<int, 2>> time_edges;  // retime: (lower, upper) prism time edges at region vertices
  std::string retime_refusal;        // why this region cannot be retimed ("" when it can)
  std::vector<int> free_of_region;   // region slot -> free column, -1 for a handle vertex
  std::vector<int> handle_of_region; // region slot -> handle column, -1 otherwise
  std::vector<int> free_vertex;      // free column -> manifold vertex
  Eigen::SparseMatrix<double> LF, LH;  // region rows x free / handle columns
  Eigen::SparseMatrix<double> LFt;
  SpdSolver solver;
  Eigen::VectorXd reach;
  std::vector<EditLayer> layers;

  // Least-squares displacements of the free vertices for a handle displacement dH (#handle x 3) and
  // target detail changes b (#region x 3): L_F^T L_F dF = L_F^T (b - L_H dH).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& dH, const Eigen::MatrixXd& b) const {
    if (free_vertex.empty()) return Eigen::MatrixXd(0, dH.cols());
    return solver.solve(LFt * (b - LH * dH));
  }
};

ManifoldEditor::ManifoldEditor(const AnimationManifold& m, EditRegion selection, const Eigen::Vector3d& pivot,
                               ManifoldEditOptions options)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.sel = std::move(selection);
  s.pivot = pivot;
  s.options = options;
  s.V = m.V;
  const std::vector<int>& region = s.sel.region;
  const int nr = static_cast<int>(region.size());
  if (nr == 0) throw Error("space-time edit: the region is empty");
  std::unordered_map<int, int> slot;  // manifold vertex -> region slot
  for (int r = 0; r < nr; ++r) slot.emplace(region[r], r);
  std::vector<char> is_handle(nr, 0);
  for (int h : s.sel.handle) {
    const auto it = slot.find(h);
    if (it == slot.end()) throw Error("space-time edit: handle vertex " + std::to_string(h) + " is not in the region");
    is_handle[it->second] = 1;
  }
  s.free_of_region.assign(nr, -1);
  s.handle_of_region.assign(nr, -1);
  int nh = 0;
  for (int r = 0; r < nr; ++r) {
    if (is_handle[r]) {
      s.handle_of_region[r] = nh++;
    } else {
      s.free_of_region[r] = static_cast<int>(s.free_vertex.size());
      s.free_vertex.push_back(region[r]);
    }
  }
  const int nf = static_cast<int>(s.free_vertex.size());

  if (s.options.weights == LaplacianWeights::Dual) {
    std::vector<int> tets;
    for (int k = 0; k < m.num_tets(); ++k)
      for (int j = 0; j < 4; ++j)
        if (slot.count(m.T(k, j))) {
          tets.push_back(k);
          break;
        }
    for (DualLaplacianRow& d : dual_laplacian_rows(m, tets, s.options.time_scale)) {
      Impl::Row row{std::move(d.vertices), std::move(d.coeffs), {}, 4};
      for (int j = 0; j < 4; ++j)
        if (const auto it = slot.find(m.T(d.tet, j)); it != slot.end()) row.turn.push_back(it->second);
      s.rows.push_back(std::move(row));
    }
    s.delta.resize(s.rows.size(), 3);
    for (size_t r = 0; r < s.rows.size(); ++r) {
      Eigen::RowVector3d d = Eigen::RowVector3d::Zero();
      for (size_t k = 0; k < s.rows[r].vertices.size(); ++k) d += s.rows[r].coeffs[k] * m.V.row(s.rows[r].vertices[k]).head<3>();
      s.delta.row(r) = d;
    }
  } else {
    const std::vector<LaplacianRow> L = manifold_laplacian_rows(m, region, s.options.weights, s.options.time_scale);
    s.delta = differential_coordinates(m, region, L).leftCols<3>();
    for (int r = 0; r < nr; ++r) {
      Impl::Row row{{region[r]}, {1.0}, {r}, 1};
      for (size_t k = 0; k < L[r].neighbours.size(); ++k) {
        row.vertices.push_back(L[r].neighbours[k]);
        row.coeffs.push_back(-L[r].weights[k]);
      }
      s.rows.push_back(std::move(row));
    }
  }
  const int nrows = static_cast<int>(s.rows.size());

  std::vector<Eigen::Triplet<double>> tf, th;
  auto put = [&](int row, int v, double value) {
    const auto it = slot.find(v);
    if (it == slot.end()) return;  // an anchor: d = 0
    const int r = it->second;
    if (s.free_of_region[r] >= 0)
      tf.emplace_back(row, s.free_of_region[r], value);
    else
      th.emplace_back(row, s.handle_of_region[r], value);
  };
  for (int r = 0; r < nrows; ++r)
    for (size_t k = 0; k < s.rows[r].vertices.size(); ++k) put(r, s.rows[r].vertices[k], s.rows[r].coeffs[k]);
  s.LF.resize(nrows, nf);
  s.LF.setFromTriplets(tf.begin(), tf.end());
  s.LH.resize(nrows, nh);
  s.LH.setFromTriplets(th.begin(), th.end());
  s.LFt = s.LF.transpose();
  if (nf > 0) {
    const Eigen::SparseMatrix<double> A = s.LFt * s.LF;
    s.solver.analyze(A);
    try {
      s.solver.factorize(A);
    } catch (const Error&) {
      throw Error("space-time edit: the region's Laplacian system is singular (a part of the region touches no anchor)");
    }
  }

  // Reach: the handle at 1, the anchors at 0, details unchanged.
  const Eigen::MatrixXd ones = Eigen::MatrixXd::Ones(nh, 1);
  const Eigen::MatrixXd sF = s.solve(ones, Eigen::MatrixXd::Zero(nrows, 1));
  s.reach.resize(nr);
  for (int r = 0; r < nr; ++r) s.reach[r] = s.free_of_region[r] >= 0 ? sF(s.free_of_region[r], 0) : 1.0;

  try {
    s.time_edges = prism_time_edges(m, region);
  } catch (const Error& e) {
    s.retime_refusal = e.what();
  }

  if (s.options.preserve_volume) {
    std::vector<double> weight;
    for (int f = 0; f < nf; ++f) {
      const double sr = std::clamp(s.reach[slot.at(s.free_vertex[f])], 0.0, 1.0);
      weight.push_back(4 * sr * (1 - sr));
    }
    s.layers = edit_layers(m, s.free_vertex, weight);
  }
}

ManifoldEditor::~ManifoldEditor() = default;

const EditRegion& ManifoldEditor::selection() const { return impl_->sel; }
const Eigen::VectorXd& ManifoldEditor::reach() const { return impl_->reach; }

MatrixX4dRow ManifoldEditor::drag(const ManifoldDrag& d) const {
  MatrixX4dRow out = impl_->V;
  drag_onto(d, out);
  return out;
}

void ManifoldEditor::drag_onto(const ManifoldDrag& d, MatrixX4dRow& out) const {
  const Impl& s = *impl_;
  const std::vector<int>& region = s.sel.region;
  const int nr = static_cast<int>(region.size());
  if (out.rows() != s.V.rows()) throw Error("space-time edit: the vertices are not the edited manifold's");
  if (!d.translation.allFinite() || !d.rotation.allFinite())
    throw Error("space-time edit: the drag's translation or rotation is not finite");
  if (!(d.rotation.transpose() * d.rotation).isApprox(Eigen::Matrix3d::Identity(), 1e-9) || d.rotation.determinant() < 0)
    throw Error("space-time edit: the drag's rotation is not a rotation matrix");
  if (!std::isfinite(d.retime)) throw Error("space-time edit: the drag's retime is not finite");
  if (d.retime != 0 && !s.retime_refusal.empty()) throw Error("space-time edit: cannot retime: " + s.retime_refusal);
  const bool turns = d.rotation != Eigen::Matrix3d::Identity();
  for (int v : region) out.row(v) = s.V.row(v);

  // The handle's targets (exact: written directly, not through the solve).
  Eigen::MatrixXd dH(s.sel.handle.size(), 3);
  for (int r = 0; r < nr; ++r) {
    const int h = s.handle_of_region[r];
    if (h < 0) continue;
    const Eigen::Vector3d p = s.V.row(region[r]).head<3>();
    const Eigen::Vector3d target = turns ? Eigen::Vector3d(d.rotation * (p - s.pivot) + s.pivot + d.translation)
                                         : Eigen::Vector3d(p + d.translation);
    out.row(region[r]).head<3>() = target;
    dH.row(h) = (target - p).transpose();
  }

  if (!turns && s.layers.empty() && s.options.linear_translation) {
    // No turn: the details are unchanged (b = 0) and every handle moves by the translation, so the
    // solve is the reach's (the handle at 1, the anchors at 0) times the translation.
    for (int r = 0; r < nr; ++r)
      if (s.free_of_region[r] >= 0) out.row(region[r]).head<3>() += s.reach[r] * d.translation.transpose();
  } else {
    // 4.2.1: each detail turns by its share s_i of the handle's rotation.
    const int nrows = static_cast<int>(s.rows.size());
    std::vector<Eigen::Matrix3d> R(nrows, Eigen::Matrix3d::Identity());
    if (turns && s.options.turn_details) {
      const Eigen::AngleAxisd aa(d.rotation);
      for (int r = 0; r < nrows; ++r) {
        double share = 0;
        for (int slot : s.rows[r].turn) share += s.reach[slot];
        share /= s.rows[r].turn_div;
        R[r] = Eigen::AngleAxisd(std::clamp(share, 0.0, 1.0) * aa.angle(), aa.axis()).toRotationMatrix();
      }
    }
    Eigen::MatrixXd b(nrows, 3);
    for (int r = 0; r < nrows; ++r) b.row(r) = ((R[r] - Eigen::Matrix3d::Identity()) * s.delta.row(r).transpose()).transpose();
    const Eigen::MatrixXd dF = s.solve(dH, b);
    for (size_t f = 0; f < s.free_vertex.size(); ++f) out.row(s.free_vertex[f]).head<3>() += dF.row(f);
    if (!s.layers.empty()) restore_layer_volumes(s.layers, out);
  }

  // Retime: t solves like x, y, z with no detail change, so its displacement is the reach times the
  // handle's (the handle lands on t + retime exactly, the anchors keep theirs).
  if (d.retime != 0) {
    for (int r = 0; r < nr; ++r)
      out(region[r], 3) = s.handle_of_region[r] >= 0 ? s.V(region[r], 3) + d.retime
                                                     : s.V(region[r], 3) + d.retime * s.reach[r];
    try {
      check_time_edges(out, s.time_edges);
    } catch (const Error&) {
      for (int v : region) out.row(v) = s.V.row(v);
      throw;
    }
  }
}

}  // namespace dfm
