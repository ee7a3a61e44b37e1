#include "core/anim/manifold_edit.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <Eigen/Geometry>
#include <Eigen/Sparse>

#include "core/anim/manifold_edit_volume.h"
#include "core/anim/manifold_laplacian.h"
#include "core/bind/cholesky.h"
#include "core/util/error.h"

namespace dfm {

struct ManifoldEditor::Impl {
  EditRegion sel;
  Eigen::Vector3d pivot;
  ManifoldEditOptions options;
  MatrixX4dRow V;                    // the original vertices
  std::vector<LaplacianRow> rows;    // one per region vertex
  Eigen::MatrixXd delta;             // #region x 3: original differential coordinates (x, y, z)
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

  s.rows = manifold_laplacian_rows(m, region, s.options.weights, s.options.time_scale);
  s.delta = differential_coordinates(m, region, s.rows).leftCols<3>();

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
  for (int r = 0; r < nr; ++r) {
    put(r, region[r], 1.0);
    for (size_t k = 0; k < s.rows[r].neighbours.size(); ++k) put(r, s.rows[r].neighbours[k], -s.rows[r].weights[k]);
  }
  s.LF.resize(nr, nf);
  s.LF.setFromTriplets(tf.begin(), tf.end());
  s.LH.resize(nr, nh);
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
  const Eigen::MatrixXd sF = s.solve(ones, Eigen::MatrixXd::Zero(nr, 1));
  s.reach.resize(nr);
  for (int r = 0; r < nr; ++r) s.reach[r] = s.free_of_region[r] >= 0 ? sF(s.free_of_region[r], 0) : 1.0;

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
  const Impl& s = *impl_;
  const std::vector<int>& region = s.sel.region;
  const int nr = static_cast<int>(region.size());
  if (!d.translation.allFinite() || !d.rotation.allFinite())
    throw Error("space-time edit: the drag's translation or rotation is not finite");
  if (!(d.rotation.transpose() * d.rotation).isApprox(Eigen::Matrix3d::Identity(), 1e-9) || d.rotation.determinant() < 0)
    throw Error("space-time edit: the drag's rotation is not a rotation matrix");
  const bool turns = d.rotation != Eigen::Matrix3d::Identity();
  MatrixX4dRow out = s.V;

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

  // 4.2.1: each detail turns by its share s_i of the handle's rotation.
  std::vector<Eigen::Matrix3d> R(nr, Eigen::Matrix3d::Identity());
  if (turns && s.options.turn_details) {
    const Eigen::AngleAxisd aa(d.rotation);
    for (int r = 0; r < nr; ++r)
      R[r] = Eigen::AngleAxisd(std::clamp(s.reach[r], 0.0, 1.0) * aa.angle(), aa.axis()).toRotationMatrix();
  }
  auto details = [&] {
    Eigen::MatrixXd b(nr, 3);
    for (int r = 0; r < nr; ++r) b.row(r) = ((R[r] - Eigen::Matrix3d::Identity()) * s.delta.row(r).transpose()).transpose();
    return b;
  };
  auto place = [&](const Eigen::MatrixXd& dF) {
    for (size_t f = 0; f < s.free_vertex.size(); ++f) out.row(s.free_vertex[f]).head<3>() += dF.row(f);
  };
  place(s.solve(dH, details()));

  if (!s.layers.empty()) restore_layer_volumes(s.layers, out);
  return out;
}

}  // namespace dfm
