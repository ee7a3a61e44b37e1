#pragma once
// Tetrahedral meshing with the TetGen executable (name from the DFM_TETGEN_EXE compile definition),
// run as a subprocess in a fresh temporary folder that is removed afterwards.
#include <string>

#include <Eigen/Core>

#include "core/mesh/mesh.h"

namespace dfm {

// A piecewise linear complex: points, triangle facets and segments (all 0-based into V).
struct Plc {
  Eigen::MatrixXd V;  // #V x 3
  Eigen::MatrixXi F;  // #F x 3 facets (may be empty: then V is tetrahedralized as a point set)
  Eigen::MatrixXi E;  // #E x 2 constraint segments (edges that must appear in the mesh)
};

struct TetgenResult {
  TetMesh mesh;            // tets positively oriented; V holds every output vertex
  Eigen::VectorXi input_to_tet;  // plc.V row -> tet vertex, -1 where TetGen dropped it (outside/duplicate)
  std::string log;         // TetGen's output
  double seconds = 0;      // wall time of the subprocess
};

// switches: TetGen's command-line switches without the dash, e.g. "pq1.414Y". 'z' (0-based output) is
// added. Switches that change the output's shape (r, N, E, o2, ...) are refused. With facets, 'p' is
// expected; without facets (a point set: plain Delaunay) p, Y, d, q and a are removed. Throws dfm::Error with TetGen's message on failure.
TetgenResult tetrahedralize(const Plc& plc, const std::string& switches = "pq1.414Y");

// The executable used (DFM_TETGEN_EXE, overridable with the environment variable DFM_TETGEN).
std::string tetgen_executable();

}  // namespace dfm
