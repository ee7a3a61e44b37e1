#include "core/pose/arap_elements.h"

#include <cmath>
#include <string>

#include <Eigen/Dense>

#include "core/util/error.h"

namespace dfm {

namespace {

// K corners (3: triangle, 4: tet), fixed-size so the 300K tets of a bind volume cost no allocation.
template <int K>
void element_matrices(const Eigen::MatrixXd& V, const Eigen::MatrixXi& elements, Eigen::MatrixXd& out) {
  Eigen::Matrix<double, 3, K - 1> E;
  Eigen::Matrix<double, 3, K> G;
  for (int e = 0; e < elements.rows(); ++e) {
    const Eigen::Vector3d p0 = V.row(elements(e, 0)).transpose();
    for (int c = 1; c < K; ++c) E.col(c - 1) = V.row(elements(e, c)).transpose() - p0;
    // Hat gradients of corners 1..K-1 are the columns of E (E^T E)^-1; corner 0's is minus their sum.
    const Eigen::Matrix<double, K - 1, K - 1> gram = E.transpose() * E;
    const double det = gram.determinant();
    const double scale = E.colwise().squaredNorm().maxCoeff();
    if (!(det > 1e-20 * std::pow(scale, K - 1)))
      throw Error(std::string(K == 3 ? "triangle " : "tet ") + std::to_string(e) + " is degenerate");
    G.template rightCols<K - 1>() = E * gram.inverse();
    G.col(0) = -G.template rightCols<K - 1>().rowwise().sum();
    const double measure = std::sqrt(det) / (K == 3 ? 2.0 : 6.0);
    Eigen::Map<Eigen::Matrix<double, K, K>>(out.col(e).data()) = measure * G.transpose() * G;
  }
}

}  // namespace

Eigen::MatrixXd arap_element_matrices(const Eigen::MatrixXd& V, const Eigen::MatrixXi& elements) {
  const int k = static_cast<int>(elements.cols());
  if (k != 3 && k != 4) throw Error("ARAP elements must be triangles or tets, got " + std::to_string(k) + " columns");
  if (elements.size() && (elements.minCoeff() < 0 || elements.maxCoeff() >= V.rows()))
    throw Error("ARAP element index out of range (" + std::to_string(V.rows()) + " vertices)");
  Eigen::MatrixXd out(k * k, elements.rows());
  if (k == 3) element_matrices<3>(V, elements, out);
  else element_matrices<4>(V, elements, out);
  return out;
}

Eigen::SparseMatrix<double> arap_laplacian(int num_vertices, const Eigen::MatrixXi& elements,
                                           const Eigen::MatrixXd& element_matrices) {
  const int k = static_cast<int>(elements.cols());
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<size_t>(elements.rows()) * k * k);
  for (int e = 0; e < elements.rows(); ++e)
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < k; ++i)
        trip.emplace_back(elements(e, i), elements(e, j), k * element_matrices(i + k * j, e));
  Eigen::SparseMatrix<double> L(num_vertices, num_vertices);
  L.setFromTriplets(trip.begin(), trip.end());
  return L;
}

}  // namespace dfm
