// The weight brush (core/scene/weight_brush.h, issue 34): each mode against its formula written here,
// rows a partition of unity, locks and the bind's rows kept, Smooth's energy, front faces only; in the
// document a stroke is one undo step that undo takes back exactly, X mirror paints the mirror handle,
// and a script's paint-weights lines give the same weights bit for bit.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "core/scene/command.h"
#include "core/scene/document.h"
#include "core/scene/script.h"
#include "core/scene/weight_brush.h"
#include "tests/weight_tools_test_meshes.h"

using namespace dfm;
using namespace dfm::test;

namespace {

// The brush profile, written from its definition: 1 within (1 - falloff) R, then 1 - 3u^2 + 2u^3.
double profile(double r, double R, double falloff) {
  if (r > R) return 0;
  const double inner = (1 - falloff) * R;
  if (r <= inner) return 1;
  const double u = (r - inner) / (R - inner);
  return 1 - 3 * u * u + 2 * u * u * u;
}

struct Strip {
  TriMesh mesh = mirror_strip();
  Eigen::MatrixXd W;
  WeightPaintSurface surface;
  explicit Strip(double asymmetry = 0.5) {
    W = strip_weights(mesh, strip_rig(), asymmetry);
    surface = weight_paint_surface(mesh.V, mesh.F);
  }
};

WeightBrush brush(WeightPaintMode mode, double radius, double strength, double falloff = 0.5, double value = 1) {
  WeightBrush b;
  b.mode = mode, b.radius = radius, b.strength = strength, b.falloff = falloff, b.value = value;
  return b;
}

Eigen::MatrixXd painted(const Strip& s, int h, const Eigen::Vector3d& c, const WeightBrush& b,
                        const std::vector<bool>& locked = {}, const std::vector<bool>& fixed = {}) {
  Eigen::MatrixXd W = s.W;
  apply_weight_dab(W, weight_dab(s.W, s.surface, h, c, b, locked, fixed));
  return W;
}

void check_partition(const Eigen::MatrixXd& W) {
  CHECK(W.minCoeff() >= 0);
  CHECK(W.maxCoeff() <= 1);
  CHECK((W.rowwise().sum().array() - 1).abs().maxCoeff() < 1e-12);
}

// One column's sum over edges of (w_a - w_b)^2.
double column_energy(const TriMesh& m, const Eigen::MatrixXd& W, int h) { return edge_energy(m, W.col(h)); }

}  // namespace

TEST_CASE("weight brush: Add raises the handle by strength times the profile, the rest rescaled; outside untouched") {
  const Strip s;
  const Eigen::Vector3d c = s.mesh.V.row(strip_vertex(10, 2)).transpose() + Eigen::Vector3d(0.013, 0.021, 0);
  const double R = 0.35, k = 0.3;
  const int h = 2;
  const Eigen::MatrixXd W = painted(s, h, c, brush(WeightPaintMode::Add, R, k));
  int inside = 0;
  for (int v = 0; v < W.rows(); ++v) {
    const double r = (s.mesh.V.row(v).transpose() - c).norm();
    if (r > R) {
      CHECK(W.row(v) == s.W.row(v));  // bit for bit
      continue;
    }
    ++inside;
    const double x = std::min(1.0, s.W(v, h) + k * profile(r, R, 0.5));
    double others = 0;
    for (int j = 0; j < W.cols(); ++j) others += j == h ? 0 : s.W(v, j);
    if (others == 0) {  // the handle holds the whole row (its own vertex): nothing else can take a share
      CHECK(W.row(v) == s.W.row(v));
      continue;
    }
    CHECK(W(v, h) == Approx(x).margin(1e-15));
    for (int j = 0; j < W.cols(); ++j)
      if (j != h) CHECK(W(v, j) == Approx(s.W(v, j) * (1 - x) / others).margin(1e-15));
  }
  CHECK(inside > 20);
  check_partition(W);
}

TEST_CASE("weight brush: Subtract, Mix and Smooth by their formulas; every mode keeps rows a partition of unity") {
  const Strip s;
  const Eigen::Vector3d c = s.mesh.V.row(strip_vertex(6, 3)).transpose();
  const double R = 0.3;
  const int h = 1;
  const Eigen::MatrixXd sub = painted(s, h, c, brush(WeightPaintMode::Subtract, R, 0.4, 0.7));
  const Eigen::MatrixXd mix = painted(s, h, c, brush(WeightPaintMode::Mix, R, 1, 0, 0.25));
  for (int v = 0; v < s.W.rows(); ++v) {
    const double r = (s.mesh.V.row(v).transpose() - c).norm();
    if (r > R || v == strip_handle_vertex(h)) continue;
    CHECK(sub(v, h) == Approx(std::max(0.0, s.W(v, h) - 0.4 * profile(r, R, 0.7))).margin(1e-15));
    CHECK(mix(v, h) == Approx(0.25).margin(1e-15));  // full strength, hard edge: the value itself
  }
  // Smooth: each weight moves toward its edge neighbours' mean before the dab (a Jacobi step).
  std::vector<std::set<int>> nbr(s.W.rows());
  for (int f = 0; f < s.mesh.num_faces(); ++f)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        if (a != b) nbr[s.mesh.F(f, a)].insert(s.mesh.F(f, b));
  const Eigen::MatrixXd sm = painted(s, h, c, brush(WeightPaintMode::Smooth, R, 0.8, 0.5));
  for (int v = 0; v < s.W.rows(); ++v) {
    const double r = (s.mesh.V.row(v).transpose() - c).norm();
    if (r > R || v == strip_handle_vertex(h)) continue;
    double mean = 0;
    for (int n : nbr[v]) mean += s.W(n, h) / nbr[v].size();
    CHECK(sm(v, h) == Approx(s.W(v, h) + 0.8 * profile(r, R, 0.5) * (mean - s.W(v, h))).margin(1e-14));
  }
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int trial = 0; trial < 40; ++trial) {
    const Eigen::Vector3d at(U(rng), 0.2 + 0.2 * U(rng), 0);
    const WeightBrush b = brush(static_cast<WeightPaintMode>(trial % 4), 0.1 + 0.3 * std::abs(U(rng)), std::abs(U(rng)),
                               std::abs(U(rng)), std::abs(U(rng)));
    check_partition(painted(s, trial % 5, at, b));
  }
}

TEST_CASE("weight brush: Smooth never raises the painted column's Dirichlet energy") {
  Strip s;
  // A rough column: handle 2's weights with a checkerboard ripple, rows renormalized.
  for (int v = 0; v < s.W.rows(); ++v) {
    s.W(v, 2) *= 1 + 0.5 * ((v % 2) ? 1 : -1);
    s.W.row(v) /= s.W.row(v).sum();
  }
  Eigen::MatrixXd W = s.W;
  double before = column_energy(s.mesh, W, 2);
  for (int dab = 0; dab < 12; ++dab) {
    const Eigen::Vector3d c(-0.6 + 0.1 * dab, 0.25, 0);
    apply_weight_dab(W, weight_dab(W, s.surface, 2, c, brush(WeightPaintMode::Smooth, 0.3, 1.0, 0.5)));
    const double after = column_energy(s.mesh, W, 2);
    CHECK(after <= before * (1 + 1e-12));
    before = after;
  }
  CHECK(before < 0.5 * column_energy(s.mesh, s.W, 2));
  check_partition(W);
}

TEST_CASE("weight brush: locked handles and fixed rows are kept; a locked handle cannot be painted") {
  const Strip s;
  const Eigen::Vector3d c = s.mesh.V.row(strip_vertex(8, 3)).transpose();
  std::vector<bool> locked(5, false), fixed(s.W.rows(), false);
  locked[1] = true;
  fixed[strip_handle_vertex(1)] = fixed[strip_handle_vertex(2)] = true;
  for (WeightPaintMode m : {WeightPaintMode::Add, WeightPaintMode::Subtract, WeightPaintMode::Mix, WeightPaintMode::Smooth}) {
    const Eigen::MatrixXd W = painted(s, 2, c, brush(m, 0.45, 0.9, 0.3, 0.6), locked, fixed);
    CHECK(W.col(1) == s.W.col(1));
    CHECK(W.row(strip_handle_vertex(1)) == s.W.row(strip_handle_vertex(1)));
    CHECK(W.row(strip_handle_vertex(2)) == s.W.row(strip_handle_vertex(2)));
    CHECK(W != s.W);
    check_partition(W);
    // Raised past what the lock leaves, the painted weight stops at 1 - locked.
    for (int v = 0; v < W.rows(); ++v) CHECK(W(v, 2) <= 1 - s.W(v, 1) + 1e-15);
  }
  CHECK_THROWS_WITH(weight_dab(s.W, s.surface, 1, c, brush(WeightPaintMode::Add, 0.3, 1), locked),
                    Catch::Contains("handle 1 is locked"));
  CHECK_THROWS_WITH(weight_dab(s.W, s.surface, 5, c, brush(WeightPaintMode::Add, 0.3, 1)), Catch::Contains("no handle 5"));
  CHECK_THROWS_WITH(weight_dab(s.W, s.surface, 0, c, brush(WeightPaintMode::Add, 0, 1)), Catch::Contains("radius"));
  CHECK_THROWS_WITH(weight_dab(s.W, s.surface, 0, c, brush(WeightPaintMode::Add, 0.3, 1.5)), Catch::Contains("strength"));
}

TEST_CASE("weight brush: front faces only paints the side facing the viewer") {
  const Strip s;  // flat, its normals +z
  const Eigen::Vector3d c = s.mesh.V.row(strip_vertex(10, 2)).transpose();
  WeightBrush b = brush(WeightPaintMode::Add, 0.3, 0.5);
  b.facing = Eigen::Vector3d(0.2, 0, -1);  // looking down onto its front
  CHECK(painted(s, 0, c, b) != s.W);
  b.facing = Eigen::Vector3d(0.2, 0, 1);  // from behind
  CHECK(painted(s, 0, c, b) == s.W);
}

namespace {

void make_document(Document& d, double asymmetry) {
  const TriMesh m = mirror_strip();
  d.set_surface(m, "strip");
  for (const PointHandle& p : strip_rig().points) d.add_point(p.position, p.name);
  d.set_weights(strip_weights(m, strip_rig(), asymmetry), {});
}

}  // namespace

TEST_CASE("weight brush in the document: a stroke is one undo step; the handles' rows kept; X mirror; scripts repeat it") {
  Document d;
  make_document(d, 0.5);
  const Eigen::MatrixXd before = d.weights();
  const int depth = d.undo_depth();
  d.begin_gesture();
  for (int i = 0; i < 5; ++i)
    d.paint_weights(3, Eigen::Vector3d(0.2 + 0.05 * i, 0.2, 0), brush(WeightPaintMode::Add, 0.2, 0.3), {4}, false);
  d.end_gesture();
  const Eigen::MatrixXd after = d.weights();
  CHECK(d.undo_depth() == depth + 1);
  CHECK(d.undo_name() == "paint weights");
  CHECK(after != before);
  CHECK(after.col(4) == before.col(4));
  for (int h = 0; h < 5; ++h) CHECK(after.row(strip_handle_vertex(h)) == before.row(strip_handle_vertex(h)));
  d.undo();
  CHECK(d.weights() == before);
  d.redo();
  CHECK(d.weights() == after);

  // The same dabs as script lines, on a fresh document: the same weights, bit for bit.
  Document by_script;
  make_document(by_script, 0.5);
  std::string text;
  for (int i = 0; i < 5; ++i) {
    const Eigen::Vector3d c(0.2 + 0.05 * i, 0.2, 0);
    text += "paint-weights 3 add " + CommandArg(c.x()).word + " 0.2 0 0.2 0.3 falloff=0.5 locked=4\n";
  }
  run_script(by_script, parse_script(text, "s.txt"), "s.txt");
  CHECK(by_script.weights() == after);

  // X mirror on symmetric weights: handle 3's dab at x = 0.4 and handle 1's at x = -0.4 (mirrors by
  // position) leave them symmetric.
  Document m;
  make_document(m, 0);
  m.paint_weights(3, Eigen::Vector3d(0.4, 0.2, 0), brush(WeightPaintMode::Add, 0.25, 0.6), {}, true);
  const Eigen::MatrixXd& M = m.weights();
  CHECK(M != strip_weights(mirror_strip(), strip_rig(), 0));
  for (int v = 0; v < M.rows(); ++v)
    for (int h = 0; h < 5; ++h) CHECK(M(v, h) == Approx(M(strip_mirror_vertex(v), kStripHandleMirror[h])).margin(1e-15));

  CHECK_THROWS_WITH(run_script(by_script, parse_script("paint-weights 3 mix 0 0 0 0.2 0.5\n", "s.txt"), "s.txt"),
                    Catch::Contains("mix needs the VALUE"));
  CHECK_THROWS_WITH(run_script(by_script, parse_script("paint-weights 3 blur 0 0 0 0.2 0.5\n", "s.txt"), "s.txt"),
                    Catch::Contains("add, subtract, mix or smooth"));
  CHECK_THROWS_WITH(run_script(by_script, parse_script("paint-weights 3 add 0 0 0 0.2 0.5 sideways\n", "s.txt"), "s.txt"),
                    Catch::Contains("unknown option 'sideways'"));
  CHECK_THROWS_WITH(run_script(by_script, parse_script("paint-weights 3 add 0 0 0 0.2 0.5 locked=3\n", "s.txt"), "s.txt"),
                    Catch::Contains("is locked"));
  Document unbound;
  unbound.set_surface(mirror_strip(), "strip");
  unbound.add_point(Eigen::Vector3d(0, 0.3, 0));
  CHECK_THROWS_WITH(run_script(unbound, parse_script("paint-weights 0 add 0 0 0 0.2 0.5\n", "s.txt"), "s.txt"),
                    Catch::Contains("weights"));
}
