#include "core/bind/bind_extrema.h"

#include <vector>

#include "core/mesh/mesh_info.h"

namespace dfm {

BindExtrema bind_local_extrema(const BindResult& res, const Eigen::MatrixXi& F) {
  const BindVolume& vol = res.volume;
  const int nt = static_cast<int>(res.tet_weights.rows()), nu = static_cast<int>(res.weights.rows());
  std::vector<char> on_handle(nt, 0), user_on_handle(nu, 0);
  for (int k = 0; k < vol.b.size(); ++k) on_handle[vol.b(k)] = 1;
  const Eigen::SparseMatrix<double>& A = vol.to_user;  // #user x #tet vertices
  for (int c = 0; c < A.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it)
      if (on_handle[c] && it.value() >= 1 - 1e-9) user_on_handle[it.row()] = 1;
  BindExtrema e;
  e.tet = count_local_extrema(vertex_neighbours(vol.tets.T, nt), res.tet_weights, on_handle);
  e.surface = count_local_extrema(vertex_neighbours(F, nu), res.weights, user_on_handle);
  return e;
}

}  // namespace dfm
