// Tet mesh dispatch by extension, and the orientation rule: TetMesh requires positively oriented tets,
// so every tet read with a negative signed volume gets its last two vertices swapped (files in the wild
// use both conventions; hand.mesh and octopus-low.mesh are already positive and load unchanged).
// Zero-volume tets are kept as they are: mesh checks can report them.
#include "core/mesh/io.h"
#include "core/mesh/io_formats.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"

#include <Eigen/Dense>

namespace dfm {

namespace io {
int orient_tets_positively(const Eigen::MatrixXd& V, Eigen::MatrixXi& T) {
  int flipped = 0;
  for (int i = 0; i < T.rows(); ++i) {
    Eigen::Vector3d a = V.row(T(i, 0)), b = V.row(T(i, 1)), c = V.row(T(i, 2)), d = V.row(T(i, 3));
    if ((b - a).cross(c - a).dot(d - a) < 0) {
      std::swap(T(i, 2), T(i, 3));
      ++flipped;
    }
  }
  return flipped;
}
}  // namespace io

bool is_tet_mesh_path(const std::string& path) {
  std::string e = file_extension(path);
  return e == "mesh" || e == "node" || e == "ele";
}

TetMesh read_tet_mesh(const std::string& path) {
  std::string e = file_extension(path);
  if (e == "mesh") return io::read_medit(path);
  if (e == "node" || e == "ele") return io::read_tetgen(path);
  throw file_error(path, 0, "unknown tet mesh extension '." + e + "' (expected .mesh, .node or .ele)");
}

void write_tet_mesh(const std::string& path, const TetMesh& mesh) {
  std::string e = file_extension(path);
  if (e == "mesh") return io::write_medit(path, mesh);
  if (e == "node" || e == "ele") return io::write_tetgen(path, mesh);
  throw file_error(path, 0, "unknown tet mesh extension '." + e + "' (expected .mesh, .node or .ele)");
}

}  // namespace dfm
