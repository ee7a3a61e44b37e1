#include "core/bind/fem.h"

#include <algorithm>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "core/util/error.h"

namespace dfm {
namespace {

// Gradients of the 4 barycentric (hat) functions of tet t (columns), and its signed volume.
// Throws on a degenerate or inverted tet: the FEM is meaningless there.
void hat_gradients(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, int t, Eigen::Matrix<double, 3, 4>& grad,
                   double& vol) {
  const Eigen::Vector3d p0 = V.row(T(t, 0)).transpose();
  Eigen::Matrix3d J;
  for (int c = 0; c < 3; ++c) J.col(c) = V.row(T(t, c + 1)).transpose() - p0;
  const double det = J.determinant();
  vol = det / 6.0;
  const double scale = J.colwise().norm().maxCoeff();
  if (!(det > 1e-14 * scale * scale * scale))
    throw Error("tet " + std::to_string(t) + " is degenerate or inverted (volume " + std::to_string(vol) +
                "): the tet mesh must be positively oriented");
  const Eigen::Matrix3d Jinv = J.inverse();  // rows = gradients of hats 1..3
  grad.block<3, 3>(0, 1) = Jinv.transpose();
  grad.col(0) = -grad.block<3, 3>(0, 1).rowwise().sum();
}

void check_indices(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  if (T.cols() != 4) throw Error("tet index matrix must have 4 columns");
  if (V.cols() != 3) throw Error("tet vertex matrix must have 3 columns");
  if (T.size() && (T.minCoeff() < 0 || T.maxCoeff() >= V.rows()))
    throw Error("tet index out of range (" + std::to_string(V.rows()) + " vertices)");
}

// Sum over tets of a_t vol_t grad(phi_i) . grad(phi_j) (a = 1 where `a` is empty), assembled straight
// into compressed columns: the pattern comes from the vertex-to-tet incidence and every element entry is
// added into its slot, instead of 16 triplets a tet sorted by setFromTriplets (the sort dominated).
Eigen::SparseMatrix<double> weighted_stiffness(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T,
                                               const Eigen::VectorXd& a) {
  check_indices(V, T);
  const int n = static_cast<int>(V.rows()), nt = static_cast<int>(T.rows());
  // Element matrices, 10 distinct entries each (upper triangle, row-major).
  std::vector<double> ke(10 * static_cast<size_t>(nt));
  Eigen::Matrix<double, 3, 4> g;
  double vol;
  for (int t = 0; t < nt; ++t) {
    hat_gradients(V, T, t, g, vol);
    const double s = a.size() ? a(t) * vol : vol;
    double* e = &ke[10 * static_cast<size_t>(t)];
    for (int i = 0, k = 0; i < 4; ++i)
      for (int j = i; j < 4; ++j) e[k++] = s * g.col(i).dot(g.col(j));
  }
  // Vertex -> incident tets (compressed), and each incidence's local corner (0..3).
  std::vector<int> tv(4 * static_cast<size_t>(nt));  // row-major copy of T: one cache line a tet
  for (int t = 0; t < nt; ++t)
    for (int c = 0; c < 4; ++c) tv[4 * static_cast<size_t>(t) + c] = T(t, c);
  std::vector<int> start(n + 1, 0), inc(4 * static_cast<size_t>(nt));
  for (int v : tv) ++start[v + 1];
  for (int v = 0; v < n; ++v) start[v + 1] += start[v];
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (size_t k = 0; k < tv.size(); ++k) inc[fill[tv[k]]++] = static_cast<int>(k);  // 4 t + corner
  }
  static constexpr int kSlot[4][4] = {{0, 1, 2, 3}, {1, 4, 5, 6}, {2, 5, 7, 8}, {3, 6, 8, 9}};
  std::vector<char> seen(n, 0);
  std::vector<int> col;
  // Pass 1: column counts, so the matrix is written in place (no growth copies: page faults are
  // costly on this class of machine).
  Eigen::SparseMatrix<double> K(n, n);
  int* outer = K.outerIndexPtr();
  outer[0] = 0;
  for (int j = 0; j < n; ++j) {
    col.clear();
    for (int p = start[j]; p < start[j + 1]; ++p) {
      const int* tet = &tv[inc[p] & ~3];
      for (int li = 0; li < 4; ++li)
        if (!seen[tet[li]]) seen[tet[li]] = 1, col.push_back(tet[li]);
    }
    for (int i : col) seen[i] = 0;
    outer[j + 1] = outer[j] + static_cast<int>(col.size());
  }
  K.resizeNonZeros(outer[n]);
  int* rows = K.innerIndexPtr();
  double* vals = K.valuePtr();
  std::vector<double> acc(n, 0.0);
  for (int j = 0; j < n; ++j) {
    col.clear();
    for (int p = start[j]; p < start[j + 1]; ++p) {
      const int t = inc[p] >> 2, lj = inc[p] & 3;
      const int* tet = &tv[4 * static_cast<size_t>(t)];
      const double* e = &ke[10 * static_cast<size_t>(t)];
      for (int li = 0; li < 4; ++li) {
        const int i = tet[li];
        if (!seen[i]) seen[i] = 1, col.push_back(i);
        acc[i] += e[kSlot[li][lj]];
      }
    }
    std::sort(col.begin(), col.end());
    int pos = outer[j];
    for (int i : col) rows[pos] = i, vals[pos] = acc[i], ++pos, acc[i] = 0.0, seen[i] = 0;
  }
  return K;
}

}  // namespace

Eigen::VectorXd tet_volumes(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  check_indices(V, T);
  Eigen::VectorXd vol(T.rows());
  for (int t = 0; t < T.rows(); ++t) {
    Eigen::Matrix3d J;
    for (int c = 0; c < 3; ++c) J.col(c) = (V.row(T(t, c + 1)) - V.row(T(t, 0))).transpose();
    vol(t) = J.determinant() / 6.0;
  }
  return vol;
}

Eigen::SparseMatrix<double> cotangent_stiffness(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  return weighted_stiffness(V, T, Eigen::VectorXd());
}

Eigen::VectorXd lumped_mass(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  const Eigen::VectorXd vol = tet_volumes(V, T);
  Eigen::VectorXd m = Eigen::VectorXd::Zero(V.rows());
  for (int t = 0; t < T.rows(); ++t)
    for (int c = 0; c < 4; ++c) m(T(t, c)) += vol(t) / 4.0;
  return m;
}

Eigen::SparseMatrix<double> tet_gradient(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  check_indices(V, T);
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(T.rows() * 12);
  Eigen::Matrix<double, 3, 4> g;
  double vol;
  for (int t = 0; t < T.rows(); ++t) {
    hat_gradients(V, T, t, g, vol);
    for (int d = 0; d < 3; ++d)
      for (int c = 0; c < 4; ++c) trip.emplace_back(3 * t + d, T(t, c), g(d, c));
  }
  Eigen::SparseMatrix<double> G(3 * T.rows(), V.rows());
  G.setFromTriplets(trip.begin(), trip.end());
  return G;
}

Eigen::SparseMatrix<double> masked_stiffness(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T,
                                             const Eigen::VectorXd& rho) {
  if (rho.size() != T.rows())
    throw Error("shape mask has " + std::to_string(rho.size()) + " values for " + std::to_string(T.rows()) + " tets");
  if (rho.size() && rho.minCoeff() < 0) throw Error("shape mask values must be >= 0");
  return weighted_stiffness(V, T, rho);
}

}  // namespace dfm
