// Surface dispatch by extension; writers check the mesh first so a bad mesh never reaches the disk.
#include "core/mesh/io.h"
#include "core/mesh/io_formats.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"

namespace dfm {
namespace {

void check_writable_mesh(const std::string& path, const TriMesh& m) {
  if (m.V.cols() != 3) throw file_error(path, 0, "cannot write: V has " + std::to_string(m.V.cols()) + " columns, not 3");
  if (m.F.cols() != 3 && m.F.rows() > 0)
    throw file_error(path, 0, "cannot write: F has " + std::to_string(m.F.cols()) + " columns, not 3");
  if (m.N.rows() != 0 && (m.N.rows() != m.V.rows() || m.N.cols() != 3))
    throw file_error(path, 0, "cannot write: N must be empty or #V x 3");
  if (m.F.size() > 0 && (m.F.minCoeff() < 0 || m.F.maxCoeff() >= m.V.rows()))
    throw file_error(path, 0, "cannot write: a face index is outside [0, " + std::to_string(m.V.rows() - 1) + "]");
}

}  // namespace

TriMesh read_surface(const std::string& path) {
  const std::string e = file_extension(path);
  if (e == "obj") return io::read_obj(path);
  if (e == "off") return io::read_off(path);
  if (e == "ply") return io::read_ply(path);
  if (e == "stl") return io::read_stl(path);
  throw file_error(path, 0, "unknown surface extension '." + e + "' (expected .obj, .off, .ply or .stl)");
}

void write_surface(const std::string& path, const TriMesh& mesh, bool binary) {
  const std::string e = file_extension(path);
  if (e != "obj" && e != "off" && e != "ply" && e != "stl")
    throw file_error(path, 0, "unknown surface extension '." + e + "' (expected .obj, .off, .ply or .stl)");
  check_writable_mesh(path, mesh);
  if (e == "obj") return io::write_obj(path, mesh);
  if (e == "off") return io::write_off(path, mesh);
  if (e == "ply") return io::write_ply(path, mesh, binary);
  return io::write_stl(path, mesh, binary);
}

}  // namespace dfm
