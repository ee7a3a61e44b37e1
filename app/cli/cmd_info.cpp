// `deform info FILE...`: what a file holds. Surfaces (.obj .off .ply .stl), tet meshes (.mesh .node
// .ele), skeletons (.tgf), matrices (.dmat) and point lists (.xyz .pts .txt). Exit 1 on a bad file.
#include <iomanip>
#include <iostream>
#include <sstream>

#include "app/cli/command.h"
#include "core/mesh/io.h"
#include "core/mesh/mesh_info.h"
#include "core/rig/rig_io.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"

namespace {

using dfm::BoundingBox;

void print_box(std::ostream& out, const BoundingBox& b) {
  out << "  bounding box: [" << b.min.x() << ", " << b.min.y() << ", " << b.min.z() << "] .. [" << b.max.x()
            << ", " << b.max.y() << ", " << b.max.z() << "]  (size " << b.diagonal().x() << " x " << b.diagonal().y()
            << " x " << b.diagonal().z() << ")\n";
}

// Shared by surfaces and tet-mesh boundaries.
void print_surface_checks(std::ostream& out, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, bool tet_boundary) {
  const bool closed = dfm::is_closed(F);
  out << "  closed: " << (closed ? "yes" : "no") << "\n"
            << "  components: " << dfm::connected_component_count(F) << "\n"
            << "  boundary edges: " << dfm::boundary_edge_count(F) << "\n"
            << "  non-manifold edges: " << dfm::non_manifold_edge_count(F) << "\n"
            << "  inconsistently oriented edges: " << dfm::inconsistent_edge_count(F) << "\n"
            << "  degenerate faces: " << dfm::degenerate_face_count(V, F) << "\n"
            << "  duplicate vertices: " << dfm::duplicate_vertex_count(V) << "\n"
            << (tet_boundary ? "  interior vertices: " : "  unreferenced vertices: ")
            << dfm::unreferenced_vertex_count(static_cast<int>(V.rows()), F) << "\n";
  if (closed) out << "  volume: " << dfm::signed_volume(V, F) << "\n";
}

void info_surface(std::ostream& out, const std::string& path) {
  dfm::TriMesh m = dfm::read_surface(path);
  out << "  kind: surface (triangle mesh)\n  vertices: " << m.num_vertices() << "\n  triangles: " << m.num_faces()
            << "\n  normals: " << (m.N.rows() ? "per vertex" : "none") << "\n";
  print_box(out, dfm::bounding_box(m.V));
  print_surface_checks(out, m.V, m.F, false);
}

void info_tet(std::ostream& out, const std::string& path) {
  dfm::TetMesh m = dfm::read_tet_mesh(path);
  out << "  kind: tet mesh\n  vertices: " << m.num_vertices() << "\n  tetrahedra: " << m.num_tets()
            << "\n  surface triangles in file: " << m.F.rows() << "\n";
  print_box(out, dfm::bounding_box(m.V));
  out << "  tet volume: " << dfm::tet_mesh_volume(m.V, m.T)
            << "\n  flat tetrahedra: " << dfm::non_positive_tet_count(m.V, m.T) << "\n";
  Eigen::MatrixXi B = dfm::tet_boundary_faces(m.T);
  out << "  boundary of the tets: " << B.rows() << " triangles\n";
  print_surface_checks(out, m.V, B, true);
}

void info_tgf(std::ostream& out, const std::string& path) {
  dfm::TgfData t = dfm::read_tgf(path);
  dfm::Rig rig;
  dfm::add_tgf_to_rig(rig, t, path);
  int roots = 0;
  for (const dfm::Bone& b : rig.skeleton.bones) roots += b.parent < 0;
  int cage_edges = 0;
  for (const dfm::Cage& c : rig.cages) cage_edges += static_cast<int>(c.edges.rows());
  out << "  kind: skeleton (TGF)\n  joints: " << t.joints.rows() << "\n  edges: " << t.edges.rows()
            << "\n  bones: " << rig.skeleton.num_bones() << " (" << roots << (roots == 1 ? " root" : " roots")
            << ")\n  point handles: " << rig.points.size() << "\n  pseudo-edges: " << rig.pseudo_edges.size()
            << "\n  cage edges: " << cage_edges << "\n  handles (weight columns): " << dfm::num_handles(rig) << "\n";
  print_box(out, dfm::bounding_box(t.joints));
}

void info_dmat(std::ostream& out, const std::string& path) {
  Eigen::MatrixXd M = dfm::read_dmat(path);
  out << "  kind: matrix (dmat)\n  size: " << M.rows() << " rows x " << M.cols() << " columns\n";
  if (M.size() > 0) out << "  min: " << M.minCoeff() << "\n  max: " << M.maxCoeff() << "\n";
}

void info_points(std::ostream& out, const std::string& path) {
  Eigen::MatrixXd P = dfm::read_points(path);
  out << "  kind: points\n  points: " << P.rows() << "\n";
  print_box(out, dfm::bounding_box(P));
}

int run(const dfm::cli::Args& args) {
  if (args.empty()) throw dfm::cli::UsageError("info needs at least one FILE");
  for (const std::string& a : args)
    if (a.rfind("--", 0) == 0) throw dfm::cli::UsageError("unknown option " + a);
  for (const std::string& path : args) {
    const std::string e = dfm::file_extension(path);
    void (*show)(std::ostream&, const std::string&) = nullptr;
    if (e == "obj" || e == "off" || e == "ply" || e == "stl") show = info_surface;
    else if (dfm::is_tet_mesh_path(path)) show = info_tet;
    else if (e == "tgf") show = info_tgf;
    else if (e == "dmat") show = info_dmat;
    else if (e == "xyz" || e == "pts" || e == "txt") show = info_points;
    else {
      dfm::require_readable_file(path);
      throw dfm::file_error(path, 0, "unknown file type '." + e +
                                         "' (known: .obj .off .ply .stl .mesh .node .ele .tgf .dmat .xyz .pts .txt)");
    }
    std::ostringstream out;  // printed only once the whole file has been read
    out << std::setprecision(6) << path << "\n";
    show(out, path);
    std::cout << out.str();
  }
  return 0;
}

dfm::cli::Register reg{"info", "print what a mesh, skeleton, matrix or points file holds",
                       "usage: deform info FILE...\n"
                       "  Prints the kind of data, counts, bounding box and mesh checks (closed or open,\n"
                       "  components, boundary and non-manifold edges, degenerate faces). Reads\n"
                       "  .obj .off .ply .stl .mesh .node/.ele .tgf .dmat and points (.xyz .pts .txt).\n"
                       "  Exit 1 with a message naming the file and the problem when a file is bad.",
                       &run};

}  // namespace
