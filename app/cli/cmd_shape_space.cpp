// `deform shape-space`: a shape space from morphing (Alexa 2002, ch. 5) over base meshes of one
// connectivity: synthesis at barycentric coordinates (Eq. 5.31's chain of pairwise morphs, linear or
// as rigid as possible) or the linear analysis of a mesh (5.5.3: least-squares coordinates, residual).
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "app/cli/command.h"
#include "core/anim/shape_space.h"
#include "core/mesh/io.h"
#include "core/util/error.h"

namespace {

const char* kUsage =
    "usage: deform shape-space --bases K0 K1 ... (--at X0 X1 ... -o OUT.obj|.ply|.off|.stl | --analyze M)\n"
    "                          [--method linear|arap]\n"
    "  --bases K0 K1 ...  two or more surfaces with the same vertices and triangles (closed for arap)\n"
    "  --at X0 X1 ...     one weight per base, summing to 1 (barycentric; base i is 1 at i, 0 elsewhere,\n"
    "                     and gives that base exactly); negative weights extrapolate\n"
    "  --method M         the pairwise morph in the chain C_k = m(B_k, C_k+1, S_k+1 / S_k): linear (default;\n"
    "                     the affine combination) or arap (as rigid as possible, per-tet rotations)\n"
    "  --analyze M        prints M's coordinates in the linear space (least squares, summing to 1), the\n"
    "                     residual (vertex distances to the nearest shape of the space) and the basis quality";

std::vector<dfm::TriMesh> read_bases(const std::vector<std::string>& files) {
  std::vector<dfm::TriMesh> out;
  for (const std::string& f : files) out.push_back(dfm::read_surface(f));
  return out;
}

int analyze(const dfm::ShapeSpace& space, const std::string& file) {
  const dfm::TriMesh M = dfm::read_surface(file);
  if (M.V.rows() != space.bases()[0].rows() || M.F.rows() != space.faces().rows() ||
      M.F.cols() != space.faces().cols() || M.F != space.faces())
    throw dfm::Error(file + ": its vertices or triangles differ from " + space.names()[0] +
                     "'s (analysis needs the bases' connectivity)");
  if (!M.V.allFinite()) throw dfm::Error(file + ": a vertex position is not finite");
  const dfm::ShapeAnalysis a = space.analyze(M.V);
  std::printf("coordinates:");
  for (int i = 0; i < a.x.size(); ++i) std::printf(" %.17g", a.x(i));
  std::printf("\nresidual: rms %.6g, max %.6g (vertex distance to the nearest shape of the space)\n", a.residual_rms,
              a.residual_max);
  std::printf("basis quality: %.6g (smallest / largest singular value; rank %d of %d)\n", a.quality(), a.rank,
              space.size() - 1);
  if (a.rank < space.size() - 1)
    std::printf("note: the bases are linearly dependent: these are the least-norm coordinates of many\n");
  return 0;
}

int run(const dfm::cli::Args& args) {
  std::vector<std::string> files, at_words;
  std::string out, analyze_file, method = "linear";
  dfm::cli::ArgReader r(args);
  while (!r.done()) {
    const std::string f = r.next();
    if (f == "--bases") files = r.values(f);
    else if (f == "--at") at_words = r.values(f);
    else if (f == "--analyze") analyze_file = r.value(f);
    else if (f == "--method") method = r.value(f);
    else if (f == "-o" || f == "--output") out = r.value(f);
    else throw dfm::cli::UsageError("unknown option " + f);
  }
  if (files.size() < 2) throw dfm::cli::UsageError("--bases needs at least two meshes");
  if (method != "linear" && method != "arap") throw dfm::cli::UsageError("--method must be linear or arap");
  if (at_words.empty() == analyze_file.empty()) throw dfm::cli::UsageError("give either --at X0 X1 ... or --analyze M");
  if (!analyze_file.empty() && method != "linear")
    throw dfm::cli::UsageError("--analyze works in the linear space (5.5.3); drop --method arap");
  if (!at_words.empty() && out.empty()) throw dfm::cli::UsageError("-o OUT is required with --at");
  Eigen::VectorXd x(at_words.size());
  for (size_t i = 0; i < at_words.size(); ++i) {
    dfm::cli::Args one{at_words[i]};
    dfm::cli::ArgReader nr(one);
    x(i) = nr.number("--at");
  }
  if (!at_words.empty()) {
    if (x.size() != static_cast<Eigen::Index>(files.size()))
      throw dfm::cli::UsageError("--at needs one weight per base: " + std::to_string(files.size()) + ", got " +
                                 std::to_string(x.size()));
    try {
      dfm::check_shape_coordinates(x, static_cast<int>(files.size()));
      dfm::morph_chain(x);  // a partial sum of 0 leaves the chain undefined
    } catch (const dfm::Error& e) {
      throw dfm::cli::UsageError(std::string("--at: ") + e.what());
    }
  }
  const auto t0 = std::chrono::steady_clock::now();
  dfm::ShapeSpace space(read_bases(files), files, dfm::parse_shape_morph(method));
  if (!analyze_file.empty()) return analyze(space, analyze_file);
  const dfm::TriMesh result{space.synthesize(x), space.faces(), {}};
  dfm::write_surface(out, result);
  std::printf("shape-space: %s over %d bases in %.3f s; wrote %s\n", method.c_str(), space.size(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), out.c_str());
  return 0;
}

dfm::cli::Register reg{"shape-space", "synthesize or analyze a shape in the space of several same-connectivity meshes",
                       kUsage, &run};

}  // namespace
