#include "core/anim/conforming_tetgen.h"

#include <string>

#include "core/bind/tetrahedralize.h"
#include "core/mesh/mesh_info.h"
#include "core/util/error.h"

namespace dfm {

ConformingSurface tetgen_conforming_start(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  Plc plc;
  plc.V = V;
  plc.F = F;
  // p alone: the constrained tetrahedralization with the fewest Steiner points; Y would forbid them.
  const TetgenResult tg = tetrahedralize(plc, "p");
  const Eigen::MatrixXi B = tet_boundary_faces(tg.mesh.T);
  const int nt = static_cast<int>(tg.mesh.V.rows()), n = static_cast<int>(V.rows());
  Eigen::VectorXi to_surface = Eigen::VectorXi::Constant(nt, -1);
  for (int i = 0; i < n; ++i) {
    const int t = tg.input_to_tet[i];
    if (t < 0) throw Error("TetGen dropped surface vertex " + std::to_string(i));
    to_surface[t] = i;
  }
  ConformingSurface s;
  int next = n;
  for (int f = 0; f < B.rows(); ++f)
    for (int j = 0; j < 3; ++j)
      if (to_surface[B(f, j)] < 0) to_surface[B(f, j)] = next++;
  s.V.resize(next, 3);
  for (int t = 0; t < nt; ++t)
    if (to_surface[t] >= 0) s.V.row(to_surface[t]) = tg.mesh.V.row(t);
  s.F.resize(B.rows(), 3);
  for (int f = 0; f < B.rows(); ++f)
    for (int j = 0; j < 3; ++j) s.F(f, j) = to_surface[B(f, j)];
  // tet_boundary_faces orients outward; an inside-out input keeps its own orientation.
  if ((signed_volume(s.V, s.F) > 0) != (signed_volume(V, F) > 0)) s.F.col(1).swap(s.F.col(2));
  s.steiner = next - n;
  s.missing = -1;
  return s;
}

}  // namespace dfm
