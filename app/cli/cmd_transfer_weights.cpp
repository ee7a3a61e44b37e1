// `deform transfer-weights`: a bound surface's weights carried onto another surface (clothing, a remesh):
// closest points within a distance and a normal angle, the rest inpainted (core/bind/weight_transfer.h).
#include <cstdio>
#include <string>

#include "app/cli/command.h"
#include "core/bind/weight_transfer.h"
#include "core/mesh/io.h"
#include "core/util/error.h"

namespace {

const char* kUsage =
    "usage: deform transfer-weights SOURCE --weights W.dmat TARGET -o W2.dmat [--distance D] [--angle A]\n"
    "  SOURCE, TARGET     surfaces (.obj .off .ply .stl); TARGET may be open, non-manifold or in pieces\n"
    "  --weights W.dmat   #SOURCE vertices x #handles\n"
    "  -o W2.dmat         #TARGET vertices x #handles: a target vertex within D of SOURCE, whose normal is\n"
    "                     within A degrees of the surface's there, takes the weights at its closest point;\n"
    "                     the others are inpainted (the smoothest weights that agree with the matched ones)\n"
    "  --distance D       default 5% of SOURCE's bounding-box diagonal\n"
    "  --angle A          default 30 degrees";

int run(const dfm::cli::Args& args) {
  std::vector<std::string> meshes;
  std::string weights, out;
  dfm::WeightTransferOptions o;
  bool distance_given = false;
  dfm::cli::ArgReader r(args);
  while (!r.done()) {
    const std::string f = r.next();
    if (f == "--weights") weights = r.value(f);
    else if (f == "-o" || f == "--output") out = r.value(f);
    else if (f == "--distance") o.max_distance = r.number(f), distance_given = true;
    else if (f == "--angle") o.max_angle_degrees = r.number(f);
    else if (!f.empty() && f[0] == '-') throw dfm::cli::UsageError("unknown option " + f);
    else meshes.push_back(f);
  }
  if (meshes.size() != 2) throw dfm::cli::UsageError("give SOURCE and TARGET surfaces");
  if (weights.empty()) throw dfm::cli::UsageError("--weights W.dmat is required");
  if (out.empty()) throw dfm::cli::UsageError("-o W2.dmat is required");
  if (!(o.max_angle_degrees >= 0 && o.max_angle_degrees <= 180)) throw dfm::cli::UsageError("--angle must be in [0, 180]");
  if (distance_given && !(o.max_distance >= 0)) throw dfm::cli::UsageError("--distance must be >= 0");
  const dfm::TriMesh source = dfm::read_surface(meshes[0]), target = dfm::read_surface(meshes[1]);
  const Eigen::MatrixXd W = dfm::read_dmat(weights);
  if (W.rows() != source.V.rows())
    throw dfm::file_error(weights, 0, "has " + std::to_string(W.rows()) + " rows but " + meshes[0] + " has " +
                                          std::to_string(source.V.rows()) + " vertices");
  dfm::WeightTransferReport rep;
  const Eigen::MatrixXd T = dfm::transfer_weights(source.V, source.F, W, target.V, target.F, o, &rep);
  dfm::write_dmat(out, T);
  std::printf("transfer-weights: %d target vertices: %d matched within %.4g, %d inpainted, %d in pieces with no match "
              "(their closest points); wrote %s (%d x %d)\n",
              static_cast<int>(target.V.rows()), rep.matched, rep.max_distance, rep.inpainted, rep.nearest, out.c_str(),
              static_cast<int>(T.rows()), static_cast<int>(T.cols()));
  return 0;
}

dfm::cli::Register reg{"transfer-weights", "carry a surface's weights onto another (clothing, a remesh)", kUsage, &run};

}  // namespace
