// Shape-space synthesis and analysis times (Alexa 2002, ch. 5; core/anim/shape_space.h) on the
// editor's default surface (the teddy) and on the armadillo: four bases (the mesh, twisted, bent,
// stretched), a simulated pad drag (three nonzero weights per frame, as a Delaunay pad gives), linear
// and ARAP. ARAP: each base's tets and factorizations are built once (ArapSource), the pair of the
// chain's first morph once; a drag frame then carries one synthesized target through a base's tets.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/anim/shape_space.h"
#include "core/mesh/io.h"

using Clock = std::chrono::steady_clock;

static double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// Twist about y by `turn` radians over the height, bend about z, or stretch along y.
static Eigen::MatrixXd warped(const Eigen::MatrixXd& V, int kind) {
  const Eigen::RowVector3d lo = V.colwise().minCoeff(), hi = V.colwise().maxCoeff(), c = 0.5 * (lo + hi);
  const double h = hi(1) - lo(1);
  Eigen::MatrixXd out = V;
  for (int i = 0; i < V.rows(); ++i) {
    const Eigen::RowVector3d p = V.row(i) - c;
    const double u = p(1) / h;  // -0.5 .. 0.5
    if (kind == 0) {
      const double a = 1.2 * u;
      out.row(i) << std::cos(a) * p(0) + std::sin(a) * p(2), p(1), -std::sin(a) * p(0) + std::cos(a) * p(2);
    } else if (kind == 1) {
      const double a = 0.8 * u;
      out.row(i) << std::cos(a) * p(0) - std::sin(a) * p(1), std::sin(a) * p(0) + std::cos(a) * p(1), p(2);
    } else {
      out.row(i) << 0.85 * p(0), 1.3 * p(1), 0.85 * p(2);
    }
    out.row(i) += c;
  }
  return out;
}

static void run_case(const std::string& path) {
  const dfm::TriMesh m = dfm::read_surface(path);
  std::vector<dfm::TriMesh> bases(4, m);
  for (int k = 0; k < 3; ++k) bases[k + 1].V = warped(m.V, k);
  std::printf("%s: %d vertices, 4 bases\n", path.c_str(), m.num_vertices());
  for (dfm::ShapeMorph morph : {dfm::ShapeMorph::Linear, dfm::ShapeMorph::Arap}) {
    const int frames = morph == dfm::ShapeMorph::Linear ? 20 : 5;
    dfm::ShapeSpace space(bases, {}, morph);
    // The pad's cursor in the triangle of bases 0, 1, 2 (the chain: C_2 = B_2, C_1 = m(B_1, B_2),
    // C_0 = m(B_0, C_1)): the first frame builds the setups, the others reuse them.
    auto t0 = Clock::now();
    space.synthesize(Eigen::Vector4d(0.3, 0.3, 0.4, 0.0));
    const double first = ms_since(t0);
    t0 = Clock::now();
    for (int f = 0; f < frames; ++f) {
      const double s = 0.1 + 0.6 * f / (frames - 1);
      space.synthesize(Eigen::Vector4d(s, 0.8 * (1 - s), 0.2 * (1 - s), 0.0));
    }
    std::printf("  %-6s first synthesis %8.1f ms, then %7.2f ms per drag frame (mean of %d)\n",
                dfm::shape_morph_name(morph), first, ms_since(t0) / frames, frames);
  }
  dfm::ShapeSpace space(bases, {}, dfm::ShapeMorph::Linear);
  const Eigen::MatrixXd M = space.synthesize(Eigen::Vector4d(0.1, 0.4, -0.2, 0.7));
  auto t0 = Clock::now();
  const dfm::ShapeAnalysis a = space.analyze(M);
  std::printf("  analysis %.2f ms: coordinates %.12f %.12f %.12f %.12f (made with 0.1 0.4 -0.2 0.7), residual rms %.2g, "
              "quality %.3f\n", ms_since(t0), a.x(0), a.x(1), a.x(2), a.x(3), a.residual_rms, a.quality());
}

// Run from the repository root (the teddy is assets/default.obj), or name the meshes.
int main(int argc, char** argv) {
  if (argc > 1) {
    for (int i = 1; i < argc; ++i) run_case(argv[i]);
    return 0;
  }
  run_case("assets/default.obj");
  run_case(std::string(DFM_DATA_DIR) + "/armadillo.obj");
  return 0;
}
