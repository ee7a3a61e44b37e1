#include "core/bind/weight_transfer.h"

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/SparseCholesky>

#include "core/bind/closest_surface_point.h"
#include "core/bind/parallel_for.h"
#include "core/bind/surface_laplacian.h"
#include "core/mesh/mesh_info.h"
#include "core/skin/skin.h"
#include "core/util/error.h"

namespace dfm {

namespace {

void check_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const char* what) {
  if (V.cols() != 3 || F.cols() != 3 || !V.allFinite()) throw Error(std::string("weight transfer: the ") + what + " must be #V x 3 finite and #F x 3");
  if (F.size() && (F.minCoeff() < 0 || F.maxCoeff() >= V.rows()))
    throw Error(std::string("weight transfer: a face index of the ") + what + " is out of range");
}

Eigen::RowVectorXd sample_weights(const SurfaceSample& s, const Eigen::MatrixXd& W) {
  return s.weight[0] * W.row(s.vertex[0]) + s.weight[1] * W.row(s.vertex[1]) + s.weight[2] * W.row(s.vertex[2]);
}

Eigen::Vector3d face_normal(const Eigen::MatrixXd& V, const SurfaceSample& s) {
  const Eigen::Vector3d a = V.row(s.vertex[0]), b = V.row(s.vertex[1]), c = V.row(s.vertex[2]);
  return (b - a).cross(c - a);
}

// Step 1: the matched rows (match[i]), their weights in out.
std::vector<char> match_closest(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& W,
                                const Eigen::MatrixXd& TV, const Eigen::MatrixXi& TF, double max_distance,
                                double max_angle, Eigen::MatrixXd& out) {
  const SurfaceTree near(V, F, max_distance);
  const Eigen::MatrixXd N = vertex_normals(TV, TF);
  const double cos_max = std::cos(max_angle * M_PI / 180.0);
  std::vector<char> match(TV.rows(), 0);
  parallel_for(static_cast<int>(TV.rows()), 0, [&](int i) {
    const SurfaceSample s = near.closest(TV.row(i).transpose());
    if (!s.found() || s.distance > max_distance) return;
    const Eigen::Vector3d n = N.row(i).transpose(), m = face_normal(V, s);
    const bool at = s.distance < 1e-12 * max_distance;  // on the source: the normal does not matter
    if (!at && !(n.norm() > 0 && m.norm() > 0 && n.normalized().dot(m.normalized()) >= cos_max)) return;
    out.row(i) = sample_weights(s, W);
    match[i] = 1;
  });
  return match;
}

// Step 2 for the pieces with no matched vertex: their closest source points' weights.
void fill_unmatched_pieces(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& W,
                           const Eigen::MatrixXd& TV, const Eigen::MatrixXi& TF, std::vector<char>& fixed,
                           Eigen::MatrixXd& out, WeightTransferReport& r) {
  const Eigen::VectorXi piece_of_face = face_components(TF);
  const int pieces = TF.rows() ? piece_of_face.maxCoeff() + 1 : 0;
  Eigen::VectorXi piece = Eigen::VectorXi::Constant(TV.rows(), -1);  // -1: on no triangle
  for (int f = 0; f < TF.rows(); ++f)
    for (int k = 0; k < 3; ++k) piece[TF(f, k)] = piece_of_face[f];
  std::vector<char> has_match(pieces, 0);
  for (Eigen::Index i = 0; i < TV.rows(); ++i)
    if (fixed[i] && piece[i] >= 0) has_match[piece[i]] = 1;
  const double diag = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  const Eigen::Vector3d far = TV.rows() ? Eigen::Vector3d((TV.colwise().maxCoeff() - TV.colwise().minCoeff()).transpose()) : Eigen::Vector3d::Zero();
  const SurfaceTree anywhere(V, F, 2 * (diag + far.norm()) + 1e-9);
  for (Eigen::Index i = 0; i < TV.rows(); ++i) {
    if (fixed[i] || (piece[i] >= 0 && has_match[piece[i]])) continue;
    out.row(i) = sample_weights(anywhere.closest(TV.row(i).transpose()), W);
    fixed[i] = 1;
    ++r.nearest;
  }
}

// Step 2: the Dirichlet energy minimized over the free rows, the fixed ones held (K_uu X = -K_uf W_f).
// A faint graph Laplacian keeps every piece connected where clamped cotangents are 0.
void inpaint_free_rows(const Eigen::MatrixXd& TV, const Eigen::MatrixXi& TF, const std::vector<char>& fixed,
                       Eigen::MatrixXd& out, WeightTransferReport& r) {
  const int n = static_cast<int>(TV.rows());
  std::vector<int> slot(n, -1);
  int nu = 0;
  for (int i = 0; i < n; ++i)
    if (!fixed[i]) slot[i] = nu++;
  r.inpainted = nu;
  if (nu == 0) return;
  Eigen::SparseMatrix<double> K = surface_cotangent_stiffness(TV, TF);
  const double scale = K.diagonal().sum() / std::max<Eigen::Index>(1, K.rows());
  K += (1e-6 * (scale > 0 ? scale : 1.0)) * uniform_stiffness(n, TF);
  std::vector<Eigen::Triplet<double>> uu;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(nu, out.cols());
  for (int c = 0; c < K.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, c); it; ++it) {
      const int row = static_cast<int>(it.row()), col = static_cast<int>(it.col());
      if (slot[row] < 0) continue;
      if (slot[col] >= 0) uu.emplace_back(slot[row], slot[col], it.value());
      else rhs.row(slot[row]) -= it.value() * out.row(col);
    }
  Eigen::SparseMatrix<double> Kuu(nu, nu);
  Kuu.setFromTriplets(uu.begin(), uu.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(Kuu);
  if (solver.info() != Eigen::Success) throw Error("weight transfer: the inpainting system could not be factored");
  const Eigen::MatrixXd X = solver.solve(rhs);
  for (int i = 0; i < n; ++i) {
    if (slot[i] < 0) continue;
    Eigen::RowVectorXd w = X.row(slot[i]).cwiseMax(0.0).cwiseMin(1.0);
    const double s = w.sum();
    out.row(i) = s > 0 ? Eigen::RowVectorXd(w / s) : Eigen::RowVectorXd::Constant(w.size(), 1.0 / w.size());
  }
}

void inpaint_unmatched(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& W,
                       const Eigen::MatrixXd& TV, const Eigen::MatrixXi& TF, std::vector<char>& fixed,
                       Eigen::MatrixXd& out, WeightTransferReport& r) {
  fill_unmatched_pieces(V, F, W, TV, TF, fixed, out, r);
  inpaint_free_rows(TV, TF, fixed, out, r);
}

}  // namespace

Eigen::MatrixXd transfer_weights(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& W,
                                 const Eigen::MatrixXd& TV, const Eigen::MatrixXi& TF,
                                 const WeightTransferOptions& o, WeightTransferReport* report) {
  check_mesh(V, F, "source");
  check_mesh(TV, TF, "target");
  if (F.rows() == 0) throw Error("weight transfer: the source has no triangles");
  if (W.rows() != V.rows() || W.cols() == 0 || !W.allFinite())
    throw Error("weight transfer: the weights are " + std::to_string(W.rows()) + " x " + std::to_string(W.cols()) +
                ", expected " + std::to_string(V.rows()) + " rows (one per source vertex)");
  const double diag = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  const double max_distance = o.max_distance >= 0 ? o.max_distance : 0.05 * diag;
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(TV.rows(), W.cols());
  std::vector<char> fixed = match_closest(V, F, W, TV, TF, std::max(max_distance, 1e-12 * diag), o.max_angle_degrees, out);
  WeightTransferReport r;
  r.max_distance = max_distance;
  for (char m : fixed) r.matched += m;
  inpaint_unmatched(V, F, W, TV, TF, fixed, out, r);
  if (report) *report = r;
  return out;
}

}  // namespace dfm
