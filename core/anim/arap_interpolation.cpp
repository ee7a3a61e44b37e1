#include "core/anim/arap_interpolation.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <deque>
#include <string>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "core/bind/fem.h"
#include "core/bind/tetrahedralize.h"
#include "core/pose/best_rotation.h"
#include "core/util/error.h"

namespace dfm {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Columns: gradients of tet t's four hat functions on the rest mesh.
Eigen::Matrix<double, 3, 4> hat_gradients(const TetMesh& m, int t) {
  Eigen::Matrix3d J;
  for (int c = 0; c < 3; ++c) J.col(c) = (m.V.row(m.T(t, c + 1)) - m.V.row(m.T(t, 0))).transpose();
  Eigen::Matrix<double, 3, 4> G;
  G.rightCols<3>() = J.inverse().transpose();
  G.col(0) = -G.rightCols<3>().rowwise().sum();
  return G;
}

Eigen::Matrix3d deformation_gradient(const Eigen::MatrixXd& X, const Eigen::MatrixXi& T, int t,
                                     const Eigen::Matrix<double, 3, 4>& G) {
  Eigen::Matrix3d F = Eigen::Matrix3d::Zero();
  for (int c = 0; c < 4; ++c) F += X.row(T(t, c)).transpose() * G.col(c).transpose();
  return F;
}

// Rows of K P = B for target gradients A_t: row i of B is sum over tets at i of vol (A_t g_i)^T.
template <class TargetOf>
Eigen::MatrixXd gradient_rhs(const TetMesh& m, const std::vector<Eigen::Matrix<double, 3, 4>>& grad,
                             const Eigen::VectorXd& vol, const TargetOf& target_of) {
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(m.V.rows(), 3);
  for (int t = 0; t < m.num_tets(); ++t) {
    const Eigen::Matrix3d A = target_of(t);
    for (int c = 0; c < 4; ++c) B.row(m.T(t, c)) += vol(t) * (A * grad[t].col(c)).transpose();
  }
  return B;
}

// Rotation vectors on one branch across face-neighbouring tets: breadth first from the tet turning
// least, each tet takes the vector among theta a, (theta -+ 2 pi) a nearest to its neighbour's.
std::vector<Eigen::Vector3d> consistent_rotation_vectors(const Eigen::MatrixXi& T, const std::vector<Eigen::Matrix3d>& R) {
  const int nt = static_cast<int>(T.rows());
  std::vector<Eigen::Vector3d> principal(nt), out(nt);
  for (int t = 0; t < nt; ++t) {
    const Eigen::AngleAxisd aa(R[t]);
    principal[t] = aa.angle() * aa.axis();
  }
  std::vector<std::pair<std::array<int, 3>, int>> faces;
  faces.reserve(4 * static_cast<size_t>(nt));
  for (int t = 0; t < nt; ++t)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> f;
      for (int c = 0, k = 0; c < 4; ++c)
        if (c != skip) f[k++] = T(t, c);
      std::sort(f.begin(), f.end());
      faces.push_back({f, t});
    }
  std::sort(faces.begin(), faces.end());
  std::vector<std::vector<int>> nbr(nt);
  for (size_t i = 0; i + 1 < faces.size(); ++i)
    if (faces[i].first == faces[i + 1].first) {
      nbr[faces[i].second].push_back(faces[i + 1].second);
      nbr[faces[i + 1].second].push_back(faces[i].second);
    }
  std::vector<char> done(nt, 0);
  for (int seed_pass = 0; seed_pass < nt; ++seed_pass) {  // one BFS per connected piece
    int seed = -1;
    for (int t = 0; t < nt; ++t)
      if (!done[t] && (seed < 0 || principal[t].norm() < principal[seed].norm())) seed = t;
    if (seed < 0) break;
    out[seed] = principal[seed];
    done[seed] = 1;
    std::deque<int> queue{seed};
    while (!queue.empty()) {
      const int t = queue.front();
      queue.pop_front();
      for (int n : nbr[t]) {
        if (done[n]) continue;
        const double theta = principal[n].norm();
        Eigen::Vector3d best = principal[n];
        if (theta > 1e-12) {
          const Eigen::Vector3d axis = principal[n] / theta;
          for (double k : {-1.0, 1.0}) {
            const Eigen::Vector3d cand = (theta + 2 * M_PI * k) * axis;
            if ((cand - out[t]).norm() < (best - out[t]).norm()) best = cand;
          }
        }
        out[n] = best;
        done[n] = 1;
        queue.push_back(n);
      }
    }
  }
  return out;
}

// K without the fixed vertex's row and column, and its column (free rows).
void split_fixed(const Eigen::SparseMatrix<double>& K, int fixed, const std::vector<int>& free_index,
                 Eigen::SparseMatrix<double>& Kff, Eigen::SparseMatrix<double>& fixed_col) {
  const int n = static_cast<int>(K.rows());
  std::vector<Eigen::Triplet<double>> ff, fc;
  for (int j = 0; j < K.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, j); it; ++it) {
      if (it.row() == fixed) continue;
      if (j == fixed) fc.emplace_back(free_index[it.row()], 0, it.value());
      else ff.emplace_back(free_index[it.row()], free_index[j], it.value());
    }
  Kff.resize(n - 1, n - 1);
  Kff.setFromTriplets(ff.begin(), ff.end());
  fixed_col.resize(n - 1, 1);
  fixed_col.setFromTriplets(fc.begin(), fc.end());
}

Eigen::Matrix3d rotation_of(const Eigen::Vector3d& r) {
  const double a = r.norm();
  return a > 0 ? Eigen::AngleAxisd(a, r / a).toRotationMatrix() : Eigen::Matrix3d::Identity();
}

}  // namespace

Eigen::MatrixXd linear_interpolation(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double t) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) throw Error("linear interpolation: the keys differ in size");
  return (1.0 - t) * a + t * b;
}

ArapSource::ArapSource(const TriMesh& k0, const ArapInterpolationOptions& opts)
    : key_(k0.V), interior_iterations_(opts.interior_iterations), symmetric_(opts.symmetric) {
  auto t0 = std::chrono::steady_clock::now();
  const TetgenResult tg = tetrahedralize(Plc{k0.V, k0.F, {}}, opts.tetgen_switches);
  rest_ = tg.mesh;
  surface_to_tet_ = tg.input_to_tet;
  if ((surface_to_tet_.array() < 0).any()) throw Error("ARAP interpolation: TetGen dropped a vertex of the first key");
  stats_.tets = rest_.num_tets();
  stats_.tet_vertices = rest_.num_vertices();
  stats_.tetrahedralize_seconds = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  const int n = rest_.num_vertices(), nt = rest_.num_tets();
  grad_.resize(nt);
  for (int t = 0; t < nt; ++t) grad_[t] = hat_gradients(rest_, t);
  vol_ = tet_volumes(rest_.V, rest_.T);
  const Eigen::SparseMatrix<double> K = cotangent_stiffness(rest_.V, rest_.T);  // sum vol G^T G

  // The interior block, for carrying a second key's interior (boundary columns kept in Kib_).
  std::vector<char> on_surface(n, 0);
  for (int i = 0; i < surface_to_tet_.size(); ++i) on_surface[surface_to_tet_(i)] = 1;
  std::vector<int> slot(n, -1);  // tet vertex -> row among the interior ones
  for (int i = 0; i < n; ++i)
    if (!on_surface[i]) slot[i] = static_cast<int>(interior_.size()), interior_.push_back(i);
  if (!interior_.empty()) {
    std::vector<Eigen::Triplet<double>> ii, ib;
    for (int j = 0; j < K.outerSize(); ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(K, j); it; ++it)
        if (slot[it.row()] >= 0) (slot[j] >= 0 ? ii : ib).emplace_back(slot[it.row()], slot[j] >= 0 ? slot[j] : j, it.value());
    Eigen::SparseMatrix<double> Kii(interior_.size(), interior_.size());
    Kib_.resize(interior_.size(), n);
    Kii.setFromTriplets(ii.begin(), ii.end());
    Kib_.setFromTriplets(ib.begin(), ib.end());
    inner_.compute(Kii);
    if (inner_.info() != Eigen::Success) throw Error("ARAP interpolation: the interior system did not factor");
  }

  // Eq. 4.26 with the vertex nearest the centroid fixed (it moves linearly): K restricted to the rest.
  const Eigen::RowVector3d centroid = rest_.V.colwise().mean();
  (rest_.V.rowwise() - centroid).rowwise().squaredNorm().minCoeff(&fixed_);
  free_index_.assign(n, -1);
  for (int i = 0, k = 0; i < n; ++i)
    if (i != fixed_) free_index_[i] = k++;
  Eigen::SparseMatrix<double> Kff;
  split_fixed(K, fixed_, free_index_, Kff, K_fixed_col_);
  solver_.compute(Kff);
  if (solver_.info() != Eigen::Success) throw Error("ARAP interpolation: the vertex-path system did not factor");
  if (symmetric_) Kff_ = std::move(Kff);
  stats_.factor_seconds = seconds_since(t0);
}

ArapInterpolation::ArapInterpolation(const TriMesh& k0, const Eigen::MatrixXd& k1, const ArapInterpolationOptions& opts) {
  if (k1.rows() != k0.V.rows() || k1.cols() != 3)
    throw Error("ARAP interpolation: the second key has " + std::to_string(k1.rows()) + " vertices, the first " +
                std::to_string(k0.V.rows()) + " (the keys must share one triangle list)");
  src_ = std::make_shared<const ArapSource>(k0, opts);
  carry(k1);
}

ArapInterpolation::ArapInterpolation(std::shared_ptr<const ArapSource> source, const Eigen::MatrixXd& k1)
    : src_(std::move(source)) {
  if (!src_) throw Error("ARAP interpolation: no source");
  if (k1.rows() != src_->surface_vertices() || k1.cols() != 3)
    throw Error("ARAP interpolation: the second key has " + std::to_string(k1.rows()) + " vertices, the first " +
                std::to_string(src_->surface_vertices()) + " (the keys must share one triangle list)");
  carry(k1);
}

void ArapInterpolation::carry(const Eigen::MatrixXd& k1) {
  const ArapSource& s = *src_;
  stats_ = s.stats_;
  key1_ = k1;
  const int n = s.rest_.num_vertices(), nt = s.rest_.num_tets();
  // The second key's interior: boundary at k1, interior harmonic, then local-global ARAP (Sorkine & Alexa 2007).
  auto t0 = std::chrono::steady_clock::now();
  target_ = s.rest_.V;
  for (int i = 0; i < k1.rows(); ++i) target_.row(s.surface_to_tet_(i)) = k1.row(i);
  if (!s.interior_.empty()) {
    Eigen::MatrixXd boundary = target_;
    for (int i : s.interior_) boundary.row(i).setZero();
    const Eigen::MatrixXd Kb = s.Kib_ * boundary;
    auto solve_interior = [&](const Eigen::MatrixXd& B) {
      Eigen::MatrixXd rhs(s.interior_.size(), 3);
      for (size_t k = 0; k < s.interior_.size(); ++k) rhs.row(k) = B.row(s.interior_[k]);
      const Eigen::MatrixXd X = s.inner_.solve(rhs - Kb);
      for (size_t k = 0; k < s.interior_.size(); ++k) target_.row(s.interior_[k]) = X.row(k);
    };
    solve_interior(Eigen::MatrixXd::Zero(n, 3));
    for (int it = 0; it < s.interior_iterations_; ++it)
      solve_interior(gradient_rhs(s.rest_, s.grad_, s.vol_, [&](int t) {
        return Eigen::Matrix3d(best_rotation(deformation_gradient(target_, s.rest_.T, t, s.grad_[t]).transpose()));
      }));
  }
  // Per tet A = R S (4.1.1), R on one branch across neighbours.
  std::vector<Eigen::Matrix3d> R(nt);
  stretch_.resize(nt);
  for (int t = 0; t < nt; ++t) {
    const Eigen::Matrix3d F = deformation_gradient(target_, s.rest_.T, t, s.grad_[t]);
    R[t] = best_rotation(F.transpose());
    const Eigen::Matrix3d S = R[t].transpose() * F;
    stretch_[t] = 0.5 * (S + S.transpose());
  }
  angle_ = consistent_rotation_vectors(s.rest_.T, R);
  if (s.symmetric_) setup_reverse();
  stats_.interior_seconds = seconds_since(t0);
}

// The second key's tets as the rest shape of E<- (Eq. 4.30). A carried tet that came out inverted has no
// rotation to interpolate from: it weighs 0 there (E-> still holds it).
void ArapInterpolation::setup_reverse() {
  const ArapSource& s = *src_;
  const TetMesh carried{target_, s.rest_.T};
  const int n = carried.num_vertices(), nt = carried.num_tets();
  vol1_ = tet_volumes(carried.V, carried.T).cwiseMax(0.0);
  grad1_.assign(nt, Eigen::Matrix<double, 3, 4>::Zero());
  std::vector<Eigen::Triplet<double>> k;
  for (int t = 0; t < nt; ++t) {
    if (vol1_(t) <= 0) continue;
    grad1_[t] = hat_gradients(carried, t);
    const Eigen::Matrix4d e = vol1_(t) * grad1_[t].transpose() * grad1_[t];  // sum vol G^T G, as K
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) k.emplace_back(carried.T(t, a), carried.T(t, b), e(a, b));
  }
  Eigen::SparseMatrix<double> K1(n, n);
  K1.setFromTriplets(k.begin(), k.end());
  split_fixed(K1, s.fixed_, s.free_index_, K1ff_, K1_fixed_col_);
}

// A(t) = R(t) ((1 - t) I + t S) (4.1.1): R turned by t times its angle on the consistent branch.
Eigen::Matrix3d ArapInterpolation::forward_target(int k, double t) const {
  return rotation_of(t * angle_[k]) * ((1.0 - t) * Eigen::Matrix3d::Identity() + t * stretch_[k]);
}

// The map from the second key's tet to time t: A^-1 = S^-1 R^T = R^T (R S^-1 R^T), polar with rotation
// R^T (the negated rotation vector, same branch) and stretch R S^-1 R^T, interpolated a fraction 1 - t.
Eigen::Matrix3d ArapInterpolation::reverse_target(int k, double t) const {
  const double u = 1.0 - t;
  const Eigen::Matrix3d R = rotation_of(angle_[k]);
  const Eigen::Matrix3d S_back = R * stretch_[k].inverse() * R.transpose();
  return rotation_of(-u * angle_[k]) * ((1.0 - u) * Eigen::Matrix3d::Identity() + u * S_back);
}

Eigen::MatrixXd ArapInterpolation::surface_of(const Eigen::MatrixXd& X, const Eigen::RowVector3d& p_fixed) const {
  const ArapSource& s = *src_;
  Eigen::MatrixXd out(s.surface_to_tet_.size(), 3);
  for (int i = 0; i < s.surface_to_tet_.size(); ++i) {
    const int v = s.surface_to_tet_(i);
    out.row(i) = v == s.fixed_ ? p_fixed : Eigen::RowVector3d(X.row(s.free_index_[v]));
  }
  return out;
}

Eigen::MatrixXd ArapInterpolation::at(double t) const {
  const ArapSource& s = *src_;
  if (t == 0.0) return s.key_;  // the keys themselves, bit for bit
  if (t == 1.0) return key1_;
  const int n = s.rest_.num_vertices();
  Eigen::MatrixXd B = gradient_rhs(s.rest_, s.grad_, s.vol_, [&](int k) { return forward_target(k, t); });
  if (s.symmetric_)
    B = (1.0 - t) * B + t * gradient_rhs(TetMesh{target_, s.rest_.T}, grad1_, vol1_, [&](int k) {
          return vol1_(k) > 0 ? reverse_target(k, t) : Eigen::Matrix3d::Zero().eval();
        });
  const Eigen::RowVector3d p_fixed = (1.0 - t) * s.rest_.V.row(s.fixed_) + t * target_.row(s.fixed_);
  Eigen::MatrixXd rhs(n - 1, 3);
  for (int i = 0; i < n; ++i)
    if (s.free_index_[i] >= 0) rhs.row(s.free_index_[i]) = B.row(i);
  if (!s.symmetric_) return surface_of(s.solver_.solve(rhs - s.K_fixed_col_ * p_fixed), p_fixed);
  // Eq. 4.28: H(t) = (1 - t) H-> + t H<- changes with t: one factorization per time (4.4.6).
  rhs -= ((1.0 - t) * s.K_fixed_col_ + t * K1_fixed_col_) * p_fixed;
  const Eigen::SparseMatrix<double> H = (1.0 - t) * s.Kff_ + t * K1ff_;
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(H);
  if (solver.info() != Eigen::Success) throw Error("ARAP interpolation: the symmetric system did not factor");
  return surface_of(solver.solve(rhs), p_fixed);
}

}  // namespace dfm
