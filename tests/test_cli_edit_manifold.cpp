// `deform edit-manifold` end to end (issue 35): the edit lands in the written file, the times are
// printed, and hostile input exits 1 naming the file without writing anything.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <array>
#include <map>

#include <catch2/catch.hpp>

#include "core/anim/manifold.h"
#include "core/anim/manifold_io.h"
#include "tests/cli_test_util.h"
#include "tests/scratch_dir.h"

using namespace dfm;
using namespace dfm::test;

namespace {

// A flat sheet over [0, 2] x [0, 1] standing still over 5 layers at t = 0..4.
AnimationManifold sheet_manifold() {
  const int nx = 21, ny = 11;
  Eigen::MatrixXd V(nx * ny, 3);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) V.row(j * nx + i) << 2.0 * i / (nx - 1), 1.0 * j / (ny - 1), 0;
  Eigen::MatrixXi F(2 * (nx - 1) * (ny - 1), 3);
  for (int j = 0, f = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const int a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
      F.row(f++) << a, b, d;
      F.row(f++) << a, d, c;
    }
  return build_manifold(std::vector<Eigen::MatrixXd>(5, V), F, {0, 1, 2, 3, 4});
}

}  // namespace

TEST_CASE("deform edit-manifold: the handle moves exactly, the rest of the file outside the region stays", "[cli]") {
  ScratchDir s("cli_edit_manifold");
  const AnimationManifold M = sheet_manifold();
  const std::string in = (s.dir / "sheet.tet4").string(), out = (s.dir / "edited.tet4").string();
  write_manifold(in, M);
  const Eigen::Vector3d C(1.0, 0.5, 0), H(1.3, 0.5, 0), move(0.0, 0.0, 0.25);
  const double R = 0.6;
  const RunResult r = run_deform(s, {"edit-manifold", in, "--region", "1.0", "0.5", "0", "0.6", "0", "4", "--handle", "1.3",
                                     "0.5", "0", "2", "--move", "0", "0", "0.25", "-o", out});
  REQUIRE(r.exit_code == 0);
  INFO(describe_run(r));
  CHECK(r.out.find("initialise seconds: ") != std::string::npos);
  CHECK(r.out.find("deform seconds: ") != std::string::npos);
  const AnimationManifold E = read_manifold(out);
  REQUIRE(E.num_vertices() == M.num_vertices());
  REQUIRE((E.T.array() == M.T.array()).all());
  int handle = 0;
  for (int v = 0; v < M.num_vertices(); ++v) {
    const Eigen::Vector3d p = M.V.row(v).head<3>().transpose();
    REQUIRE(E.V(v, 3) == M.V(v, 3));
    if (M.V(v, 3) == 2 && (p - H).norm() <= R / 4) {  // the handle rule, by brute force
      ++handle;
      for (int c = 0; c < 3; ++c) REQUIRE(E.V(v, c) == M.V(v, c) + move[c]);
    } else if ((p - C).norm() > R) {
      REQUIRE((E.V.row(v).array() == M.V.row(v).array()).all());
    }
  }
  REQUIRE(handle > 5);
  // The middle of the region rises part of the way, at the handle's time and a layer away.
  const int mid = 5 * 21 + 10;  // (1.0, 0.5) on a layer
  CHECK(E.V(2 * M.num_vertices() / 5 + mid, 2) > 0.02);
  CHECK(E.V(1 * M.num_vertices() / 5 + mid, 2) > 0.0);
}

TEST_CASE("deform edit-manifold --brush: a brushed ball widens the region, the rest of the file stays", "[cli]") {
  ScratchDir s("cli_edit_manifold_brush");
  const AnimationManifold M = sheet_manifold();
  const std::string in = (s.dir / "sheet.tet4").string(), out = (s.dir / "brushed.tet4").string();
  write_manifold(in, M);
  // Region balls of radius 0.3 at x = 1.0 and (brushed) x = 1.4, over the whole animation; handle at 1.0.
  const Eigen::Vector3d C(1.0, 0.5, 0), B(1.4, 0.5, 0);
  const double R = 0.3;
  const RunResult r = run_deform(s, {"edit-manifold", in, "--region", "1.0", "0.5", "0", "0.3", "0", "4", "--brush", "1.4",
                                     "0.5", "0", "--handle", "1.0", "0.5", "0", "2", "--move", "0", "0", "0.25", "-o", out});
  INFO(describe_run(r));
  REQUIRE(r.exit_code == 0);
  const AnimationManifold E = read_manifold(out);
  REQUIRE(E.num_vertices() == M.num_vertices());
  int moved_in_brush = 0;
  for (int v = 0; v < M.num_vertices(); ++v) {
    const Eigen::Vector3d p = M.V.row(v).head<3>().transpose();
    const bool in_c = (p - C).norm() <= R, in_b = (p - B).norm() <= R;
    if (!in_c && !in_b) REQUIRE((E.V.row(v).array() == M.V.row(v).array()).all());  // outside both balls
    if (in_b && !in_c && E.V(v, 2) != M.V(v, 2)) ++moved_in_brush;
  }
  CHECK(moved_in_brush > 5);  // the brushed ball's vertices follow the drag
  // A bad --brush is a usage error naming the option.
  const RunResult bad = run_deform(s, {"edit-manifold", in, "--region", "1.0", "0.5", "0", "0.3", "0", "4", "--brush", "1.4",
                                       "--handle", "1.0", "0.5", "0", "2", "--move", "0", "0", "0.25", "-o", out});
  CHECK(bad.exit_code != 0);
  CHECK(bad.err.find("--brush") != std::string::npos);
}

TEST_CASE("deform edit-manifold: hostile input exits 1 naming the file, nothing written", "[cli]") {
  ScratchDir s("cli_edit_manifold_bad");
  const std::string in = (s.dir / "sheet.tet4").string(), out = (s.dir / "never.tet4").string();
  write_manifold(in, sheet_manifold());
  std::ofstream(s.dir / "junk.tet4") << "not a manifold\n";
  const std::string junk = (s.dir / "junk.tet4").string(), missing = (s.dir / "missing.tet4").string();
  struct Case {
    std::vector<std::string> args;
    std::string says;
  };
  const std::vector<Case> cases = {
      {{in, "--region", "9", "9", "9", "0.6", "0", "4", "--handle", "9", "9", "9", "2"}, "no manifold vertex"},
      {{in, "--region", "1", "0.5", "0", "0.6", "6", "7", "--handle", "1", "0.5", "0", "6.5"}, "outside the animation"},
      {{in, "--region", "1", "0.5", "0", "0.6", "0", "4", "--handle", "1.9", "0.9", "0", "2"}, "no region vertex"},
      {{in, "--region", "1", "0.5", "0", "0.6", "1", "3", "--handle", "1", "0.5", "0", "3.5"}, "outside the window"},
      {{missing, "--region", "1", "0.5", "0", "0.6", "0", "4", "--handle", "1", "0.5", "0", "2"}, "missing.tet4"},
      {{junk, "--region", "1", "0.5", "0", "0.6", "0", "4", "--handle", "1", "0.5", "0", "2"}, "junk.tet4"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args = {"edit-manifold"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    args.insert(args.end(), {"--move", "0", "0", "0.1", "-o", out});
    const RunResult r = run_deform(s, args);
    INFO(describe_run(r));
    CHECK(r.exit_code == 1);
    CHECK(r.err.find(c.says) != std::string::npos);
    CHECK(r.err.find(c.args[0] == junk || c.args[0] == missing ? c.args[0] : in) != std::string::npos);
    CHECK(!std::filesystem::exists(out));
  }
  const RunResult usage = run_deform(s, {"edit-manifold", in, "--region", "1", "0.5", "0", "0.6", "0", "4", "-o", out});
  CHECK(usage.exit_code == 2);
  // --volume needs closed layers: the sheet is open.
  const RunResult open_sheet = run_deform(s, {"edit-manifold", in, "--region", "1", "0.5", "0", "0.6", "0", "4", "--handle", "1",
                                              "0.5", "0", "2", "--move", "0", "0", "0.1", "--volume", "-o", out});
  CHECK(open_sheet.exit_code == 1);
  CHECK(open_sheet.err.find("not a closed surface") != std::string::npos);
  CHECK(open_sheet.err.find(in) != std::string::npos);
  CHECK(!std::filesystem::exists(out));
  const RunResult bad_weights = run_deform(s, {"edit-manifold", in, "--region", "1", "0.5", "0", "0.6", "0", "4", "--handle", "1",
                                               "0.5", "0", "2", "--move", "0", "0", "0.1", "--weights", "cubic", "-o", out});
  CHECK(bad_weights.exit_code == 2);
  CHECK(bad_weights.err.find("cubic") != std::string::npos);
  // Each weighting scheme runs through the CLI and keeps the handle exact (checked in the core tests).
  for (const char* w : {"equal", "reciprocal", "primal-boundary", "dual"}) {
    const RunResult r = run_deform(s, {"edit-manifold", in, "--region", "1", "0.5", "0", "0.6", "0", "4", "--handle", "1", "0.5",
                                       "0", "2", "--move", "0", "0", "0.1", "--rotate", "0", "1", "0", "20", "--weights", w, "-o", out});
    INFO(describe_run(r));
    CHECK(r.exit_code == 0);
    std::filesystem::remove(out);
  }
}

TEST_CASE("deform edit-manifold --retime: the handle moves in t exactly, a fold is refused", "[cli]") {
  ScratchDir s("cli_edit_manifold_retime");
  const AnimationManifold M = sheet_manifold();
  const std::string in = (s.dir / "sheet.tet4").string(), out = (s.dir / "retimed.tet4").string();
  write_manifold(in, M);
  // The window [0.5, 3.5] holds layer 2's neighbourhood (layers 1 and 3 anchor it).
  auto args = [&](const char* dt) {
    return std::vector<std::string>{"edit-manifold", in, "--region", "1.0", "0.5", "0", "0.6", "0.5", "3.5", "--handle", "1.3",
                                    "0.5", "0", "2", "--move", "0", "0", "0.1", "--retime", dt, "-o", out};
  };
  const RunResult r = run_deform(s, args("0.25"));
  INFO(describe_run(r));
  REQUIRE(r.exit_code == 0);
  const AnimationManifold E = read_manifold(out);  // read back: a valid manifold (slabs merged)
  int handle = 0, moved_t = 0;
  for (int v = 0; v < M.num_vertices(); ++v) {
    const Eigen::Vector3d p = M.V.row(v).head<3>().transpose();
    if (M.V(v, 3) == 2 && (p - Eigen::Vector3d(1.3, 0.5, 0)).norm() <= 0.6 / 4) {
      ++handle;
      REQUIRE(E.V(v, 3) == 2.25);
    }
    if (M.V(v, 3) != 2) REQUIRE(E.V(v, 3) == M.V(v, 3));  // layers 1 and 3 are anchors or outside
    moved_t += E.V(v, 3) != M.V(v, 3);
  }
  REQUIRE(handle > 5);
  REQUIRE(moved_t > handle);  // the region follows in t by its reach
  CHECK(E.num_layers() == 4);  // the two slabs around layer 2 are one now
  std::filesystem::remove(out);
  const RunResult fold = run_deform(s, args("1.5"));  // past layer 3, which stays
  CHECK(fold.exit_code == 1);
  CHECK(fold.err.find("folds the manifold in time") != std::string::npos);
  CHECK(!std::filesystem::exists(out));
}

TEST_CASE("deform edit-manifold --refine: refines the layer mesh where the pull stretched, the handle exact, with --retime",
          "[cli]") {
  ScratchDir s("cli_edit_manifold_refine");
  const AnimationManifold M = sheet_manifold();
  const int n = M.prism_slabs.front().count;
  const std::string in = (s.dir / "sheet.tet4").string(), out = (s.dir / "refined.tet4").string();
  write_manifold(in, M);
  const Eigen::Vector3d C(1.0, 0.5, 0), H(1.0, 0.5, 0), move(0.0, 0.0, 0.5);
  const double R = 0.6;
  auto args = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = {"edit-manifold", in, "--region", "1.0", "0.5", "0", "0.6", "1", "3", "--handle", "1.0",
                                  "0.5", "0", "2", "--move", "0", "0", "0.5", "--refine", "-o", out};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  const RunResult r = run_deform(s, args({}));
  INFO(describe_run(r));
  REQUIRE(r.exit_code == 0);
  const size_t at = r.out.find("refine: ");
  REQUIRE(at != std::string::npos);
  int added = 0, rounds = 0;
  REQUIRE(std::sscanf(r.out.c_str() + at, "refine: %d vertices added to each layer in %d rounds", &added, &rounds) == 2);
  CHECK(added > 0);
  CHECK(rounds == 1);
  const AnimationManifold E = read_manifold(out);
  const int rn = n + added;
  REQUIRE(E.num_vertices() == 5 * rn);  // every layer refined alike
  for (const PrismSlab& p : E.prism_slabs) CHECK(p.is_prism());
  // Each layer's vertices by position (x, y, t bit for bit): the original vertices are all there, where
  // the edit put them (the handle moved exactly, the rest of the sheet outside the region unmoved).
  std::map<std::array<double, 3>, Eigen::RowVector4d> by_place;
  for (int v = 0; v < E.num_vertices(); ++v) by_place[{E.V(v, 0), E.V(v, 1), E.V(v, 3)}] = E.V.row(v);
  int handle = 0;
  for (int layer = 0; layer < 5; ++layer)
    for (int v = 0; v < n; ++v) {
      const Eigen::RowVector4d a = M.V.row(layer * n + v);
      const Eigen::Vector3d p = a.head<3>().transpose();
      const auto it = by_place.find({a[0], a[1], a[3]});
      REQUIRE(it != by_place.end());
      const Eigen::RowVector4d b = it->second;
      if (layer == 2 && (p - H).norm() <= R / 4) {  // the handle rule, by brute force
        ++handle;
        for (int c = 0; c < 3; ++c) REQUIRE(b[c] == a[c] + move[c]);
      } else if ((p - C).norm() > R || layer != 2) {  // outside the region (layers 1 and 3 anchor it)
        REQUIRE((b.array() == a.array()).all());
      }
    }
  REQUIRE(handle > 5);
  // The sheet stays in its plane wherever the edit did not move it (every layer but 2); the new vertices
  // lie near the region.
  auto far = [&](const AnimationManifold& X) {
    int count = 0;
    for (int v = 0; v < X.num_vertices(); ++v) count += (Eigen::Vector3d(X.V(v, 0), X.V(v, 1), 0) - C).norm() > R + 0.3;
    return count;
  };
  for (int v = 0; v < E.num_vertices(); ++v)
    if (E.V(v, 3) != 2) CHECK(E.V(v, 2) == 0);
  CHECK(far(E) == far(M));
  // With a retime: the handle's time moves too, and the slabs around it merge.
  std::filesystem::remove(out);
  const RunResult rt = run_deform(s, args({"--retime", "0.1"}));
  INFO(describe_run(rt));
  REQUIRE(rt.exit_code == 0);
  const AnimationManifold T = read_manifold(out);
  CHECK(T.num_vertices() == 5 * rn);
  CHECK(T.num_layers() == 4);
  double latest = 0;
  for (int v = 2 * rn; v < 3 * rn; ++v) latest = std::max(latest, T.V(v, 3));
  CHECK(latest == Approx(2.1).epsilon(1e-12));
}
