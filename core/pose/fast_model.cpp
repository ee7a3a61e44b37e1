#include "core/pose/fast_model.h"

#include <chrono>
#include <string>
#include <vector>

#include <Eigen/Sparse>

#include "core/pose/arap_elements.h"
#include "core/pose/weight_clusters.h"
#include "core/skin/lbs.h"
#include "core/util/error.h"

namespace dfm {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Kt = K M, accumulated element by element without forming K (3r x #V): element e adds, to the cluster
// of each of its corners, sum_ij Le_ij v_j e_i^T (the rest differential coordinates of Eq. 7.13).
Eigen::MatrixXd reduced_rotation_term(const Eigen::MatrixXd& V, const Eigen::MatrixXi& elements,
                                      const Eigen::MatrixXd& Le, const Eigen::VectorXi& cluster,
                                      const Eigen::SparseMatrix<double, Eigen::RowMajor>& M, int clusters) {
  const int k = static_cast<int>(elements.cols());
  Eigen::MatrixXd Kt = Eigen::MatrixXd::Zero(3 * clusters, M.cols());
  using Small = Eigen::Matrix<double, Eigen::Dynamic, 3, 0, 4, 3>;  // no heap per element
  Small Y(k, 3), Q(k, 3);
  for (int e = 0; e < elements.rows(); ++e) {
    for (int i = 0; i < k; ++i) Y.row(i) = V.row(elements(e, i));
    Q.noalias() = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 4, 4>>(Le.col(e).data(), k, k) * Y;
    // Corners sharing a cluster add the same term: once, times their count.
    int cl[4], mult[4], distinct = 0;
    for (int corner = 0; corner < k; ++corner) {
      const int c = cluster(elements(e, corner));
      int d = 0;
      while (d < distinct && cl[d] != c) ++d;
      if (d == distinct) cl[distinct] = c, mult[distinct++] = 0;
      ++mult[d];
    }
    for (int d = 0; d < distinct; ++d)
      for (int i = 0; i < k; ++i)
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(M, elements(e, i)); it; ++it)
          Kt.block<3, 1>(3 * cl[d], it.col()) += (mult[d] * it.value()) * Q.row(i).transpose();
  }
  return Kt;
}

}  // namespace

FastModel fast_model(const Eigen::MatrixXd& V, const Eigen::MatrixXi& elements, const Eigen::MatrixXd& W,
                     const FastModelOptions& opts) {
  if (V.cols() != 3) throw Error("FAST: the energy mesh's vertices must be #V x 3");
  if (W.rows() != V.rows())
    throw Error("FAST: " + std::to_string(W.rows()) + " weight rows for " + std::to_string(V.rows()) +
                " energy-mesh vertices");
  if (W.cols() == 0) throw Error("FAST: no handles");
  FastModel model;
  model.handles = static_cast<int>(W.cols());
  auto t0 = std::chrono::steady_clock::now();
  const WeightClusters clusters =
      weight_clusters(W, opts.clusters > 0 ? opts.clusters : 2 * model.handles, opts.kmeans_iterations, opts.seed);
  model.clusters = clusters.count;
  model.cluster_seconds = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  const Eigen::MatrixXd Le = arap_element_matrices(V, elements);
  const Eigen::SparseMatrix<double> L = arap_laplacian(static_cast<int>(V.rows()), elements, Le);
  const Eigen::SparseMatrix<double, Eigen::RowMajor> M = sparse_lbs_matrix(V, W);
  const Eigen::MatrixXd LM = L * M;
  model.Lt = M.transpose() * LM;
  model.Lt = 0.5 * (model.Lt + model.Lt.transpose()).eval();
  model.Kt = reduced_rotation_term(V, elements, Le, clusters.cluster, M, model.clusters);
  model.rest_term = 0.5 * (V.transpose() * (L * V)).trace();
  model.assembly_seconds = seconds_since(t0);
  return model;
}

}  // namespace dfm
