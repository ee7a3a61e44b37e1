// Space-time edits through the document and the script (issue 35): edit-region + edit-drag move the
// frame at the handle's time (the handle lands where it is dragged) and leave frames before the
// window bit for bit; the scene file keeps the edit and replays it; undo restores the unedited frame.
#include <catch2/catch.hpp>

#include <filesystem>
#include <map>
#include <unistd.h>

#include "core/anim/manifold_edit.h"
#include "core/anim/manifold_normals.h"
#include "core/scene/command.h"
#include "core/scene/key_surfaces.h"
#include "core/scene/script.h"
#include "core/scene/space_time_edit.h"
#include "core/util/error.h"
#include "tests/space_time_test_scene.h"
#include "tests/transition_test_meshes.h"

using namespace dfm;
using dfm::test::make_keyed;
namespace fs = std::filesystem;

namespace {

TriMesh frame_at(Document& d, double t) {
  d.set_time(t);
  return posed_surface(d);
}

// The frame's vertex nearest p (slices keep the surface's vertex order between keys of one connectivity).
int nearest(const TriMesh& m, const Eigen::Vector3d& p) {
  int best = 0;
  for (int i = 1; i < m.V.rows(); ++i)
    if ((m.V.row(i).transpose() - p).norm() < (m.V.row(best).transpose() - p).norm()) best = i;
  return best;
}

// A scene file's path in a folder of its own, removed with it (one per test: ctest runs them in parallel).
struct ScratchScene {
  fs::path dir;
  std::string path;
  explicit ScratchScene(const std::string& name)
      : dir(fs::temp_directory_path() / ("dfm_space_time_" + name + "_" + std::to_string(::getpid()))),
        path((dir / "s.scene.json").string()) {
    fs::create_directories(dir);
  }
  ~ScratchScene() { fs::remove_all(dir); }
  // d saved here, then loaded into e.
  void round_trip(Document& d, Document& e) const {
    d.save_scene(path);
    e.load_scene(path);
  }
};

void run(Document& d, const std::string& text) { run_script(d, parse_script(text, "s.txt"), "s.txt"); }

}  // namespace

TEST_CASE("edit-region + edit-drag: the handle lands where dragged, frames before the window stay bit for bit",
          "[script][space-time]") {
  Document d;
  make_keyed(d);
  // In-betweens 4: layers at 0, 0.4, ..., 2. The window [0.8, 2] holds layers 1.2 .. 2 (a layer vertex's
  // star must lie in the window), so the slabs before 0.8 hold no region vertex.
  const TriMesh before0 = frame_at(d, 0), before04 = frame_at(d, 0.4), before06 = frame_at(d, 0.6);
  const TriMesh mid = frame_at(d, 1.2);
  const int h = nearest(mid, {2.0, 0.4, 0});
  const Eigen::Vector3d hp = mid.V.row(h).transpose();
  char line[256];
  std::snprintf(line, sizeof line, "set-time 1.2\nedit-region %.17g %.17g %.17g 1.2 0.8 2\nedit-drag %.17g %.17g %.17g 0 0 0.5\n",
                hp.x(), hp.y(), hp.z(), hp.x(), hp.y(), hp.z());
  const int depth = d.undo_depth();
  run(d, line);
  REQUIRE(d.space_time_edits().size() == 1);
  CHECK(d.undo_depth() == depth + 2);  // edit-region, edit-drag: one step each
  const TriMesh edited = frame_at(d, 1.2);
  REQUIRE(edited.V.rows() == mid.V.rows());
  CHECK((edited.V.row(h).transpose() - (hp + Eigen::Vector3d(0, 0, 0.5))).norm() < 1e-9);
  CHECK((edited.V - mid.V).cwiseAbs().maxCoeff() > 0.4);
  // Far from the region (the -x end) nothing moves.
  const int far = nearest(mid, {-2, 0, 0});
  CHECK(edited.V.row(far) == mid.V.row(far));
  // Outside the window: bit for bit.
  CHECK(frame_at(d, 0).V == before0.V);
  CHECK(frame_at(d, 0.4).V == before04.V);
  CHECK(frame_at(d, 0.6).V == before06.V);
  // The view's normals after the edit: only the window's rows summed again, the same bits as a full pass.
  {
    Document keys_only;
    make_keyed(keys_only);
    const AnimationManifold base = document_manifold(keys_only), edited_m = document_manifold(d);
    CHECK(edited_vertex_normals(edited_m, base.V, manifold_vertex_normals(base), d.space_time_edits()) ==
          manifold_vertex_normals(edited_m));
  }

  // The same handle again adds to its move (still one edit); undo takes that drag back.
  std::snprintf(line, sizeof line, "set-time 1.2\nedit-drag %.17g %.17g %.17g 0 0 0.25\n", hp.x(), hp.y(), hp.z());
  run(d, line);
  REQUIRE(d.space_time_edits().size() == 1);
  CHECK(d.space_time_edits()[0].move.isApprox(Eigen::Vector3d(0, 0, 0.75)));
  run(d, "undo\n");
  CHECK(frame_at(d, 1.2).V == edited.V);
  // Undo the first drag and the region: the unedited frame, bit for bit.
  run(d, "undo\nundo\n");
  CHECK(d.space_time_edits().empty());
  CHECK(frame_at(d, 1.2).V == mid.V);
}

TEST_CASE("a scene round trip keeps the space-time edit and replays it; edit-clear drops it", "[script][space-time]") {
  const ScratchScene scratch("edit");
  Document d;
  make_keyed(d);
  const TriMesh mid = frame_at(d, 1.2);
  const Eigen::Vector3d hp = mid.V.row(nearest(mid, {2.0, 0.4, 0})).transpose();
  char line[256];
  std::snprintf(line, sizeof line, "set-time 1.2\nedit-region %.17g %.17g %.17g 1.2 0.8 2\nedit-drag %.17g %.17g %.17g 0.1 0 0.5\n",
                hp.x(), hp.y(), hp.z(), hp.x(), hp.y(), hp.z());
  run(d, line);
  const TriMesh edited = frame_at(d, 1.2), late = frame_at(d, 1.7);
  Document e;
  scratch.round_trip(d, e);
  REQUIRE(e.space_time_edits().size() == 1);
  CHECK(e.space_time_edits()[0] == d.space_time_edits()[0]);
  CHECK(frame_at(e, 1.2).V == edited.V);
  CHECK(frame_at(e, 1.7).V == late.V);
  run(e, "edit-clear\n");
  CHECK(e.space_time_edits().empty());
  CHECK(frame_at(e, 1.2).V == mid.V);
}

TEST_CASE("edit-refine (4.5.1): the edit made again on a finer layer mesh, undoable, kept by the scene; a drag "
          "unrefines it", "[script][space-time]") {
  const ScratchScene scratch("refine");
  Document d;
  make_keyed(d);
  const TriMesh before0 = frame_at(d, 0), mid = frame_at(d, 1.2);
  const int h = nearest(mid, {2.0, 0.4, 0});
  const Eigen::Vector3d hp = mid.V.row(h).transpose();
  REQUIRE_THROWS_WITH(run(d, "edit-refine\n"), Catch::Contains("no space-time edit to refine"));
  char line[256];
  std::snprintf(line, sizeof line, "set-time 1.2\nedit-region %.17g %.17g %.17g 1.2 0.8 2\nedit-drag %.17g %.17g %.17g 0 0 1.5\n",
                hp.x(), hp.y(), hp.z(), hp.x(), hp.y(), hp.z());
  run(d, line);
  const TriMesh edited = frame_at(d, 1.2);
  const int depth = d.undo_depth();
  run(d, "edit-refine\n");
  CHECK(d.undo_depth() == depth + 1);
  REQUIRE(d.space_time_edits().size() == 1);
  CHECK(d.space_time_edits()[0].refine);
  const TriMesh refined = frame_at(d, 1.2);
  const Eigen::Index n = mid.V.rows();
  REQUIRE(refined.V.rows() > n);
  CHECK(refined.V.row(nearest(refined, edited.V.row(h).transpose())) == edited.V.row(h));  // the handle, exactly
  CHECK(dfm::test::euler_characteristic(refined.F) == dfm::test::euler_characteristic(mid.F));
  // Outside the window: the original vertices bit for bit, the new ones on the unmoved surface's edges.
  const TriMesh refined0 = frame_at(d, 0);
  CHECK(refined0.V.rows() == refined.V.rows());
  for (Eigen::Index v = 0; v < n; ++v) CHECK(refined0.V.row(nearest(refined0, before0.V.row(v).transpose())) == before0.V.row(v));
  {
    Document keys_only;
    make_keyed(keys_only);
    const AnimationManifold base = document_manifold(keys_only), edited_m = document_manifold(d);
    CHECK(edited_vertex_normals(edited_m, base.V, manifold_vertex_normals(base), d.space_time_edits()) ==
          manifold_vertex_normals(edited_m));
  }
  REQUIRE_THROWS_WITH(run(d, "edit-refine\n"), Catch::Contains("refined already"));
  // The scene keeps it and replays the same frame.
  Document e;
  scratch.round_trip(d, e);
  REQUIRE(e.space_time_edits().size() == 1);
  CHECK(e.space_time_edits()[0] == d.space_time_edits()[0]);
  CHECK(frame_at(e, 1.2).V == refined.V);
  // Undo: the unrefined edit, bit for bit. A new drag of the edit is made unrefined.
  run(d, "undo\n");
  CHECK(frame_at(d, 1.2).V == edited.V);
  run(d, "edit-refine\n");
  std::snprintf(line, sizeof line, "set-time 1.2\nedit-drag %.17g %.17g %.17g 0 0 0.1\n", hp.x(), hp.y(), hp.z());
  run(d, line);
  CHECK(!d.space_time_edits()[0].refine);
  CHECK(frame_at(d, 1.2).V.rows() == n);
}

TEST_CASE("edit-brush: more balls of the region's radius before its drag; the drag moves what they hold; the scene "
          "keeps them", "[script][space-time]") {
  const ScratchScene scratch("brush");
  Document d;
  make_keyed(d);
  const TriMesh mid = frame_at(d, 1.2);
  const int h = nearest(mid, {2.0, 0.4, 0}), far = nearest(mid, {1.1, 0.4, 0});
  const Eigen::Vector3d hp = mid.V.row(h).transpose(), fp = mid.V.row(far).transpose();
  // Outside a ball of radius 0.6 round the handle; the brushed ball overlaps it (one region).
  REQUIRE((fp - hp).norm() > 0.7);
  REQUIRE((fp - hp).norm() < 1.1);
  char line[400];
  std::snprintf(line, sizeof line, "set-time 1.2\nedit-region %.17g %.17g %.17g 0.6 0.8 2\nedit-brush %.17g %.17g %.17g\n",
                hp.x(), hp.y(), hp.z(), fp.x(), fp.y(), fp.z());
  run(d, line);
  REQUIRE(d.space_time_edits().size() == 1);
  REQUIRE(d.space_time_edits()[0].region.dabs.size() == 1);
  std::snprintf(line, sizeof line, "edit-drag %.17g %.17g %.17g 0 0 0.5\n", hp.x(), hp.y(), hp.z());
  run(d, line);
  const TriMesh edited = frame_at(d, 1.2);
  CHECK((edited.V.row(h).transpose() - (hp + Eigen::Vector3d(0, 0, 0.5))).norm() < 1e-9);
  CHECK(edited.V.row(far) != mid.V.row(far));  // the brushed ball's vertex moved with the region
  // Without the brushed ball, that vertex stays (it is outside the region).
  {
    Document plain;
    make_keyed(plain);
    std::snprintf(line, sizeof line, "set-time 1.2\nedit-region %.17g %.17g %.17g 0.6 0.8 2\nedit-drag %.17g %.17g %.17g 0 0 0.5\n",
                  hp.x(), hp.y(), hp.z(), hp.x(), hp.y(), hp.z());
    run(plain, line);
    CHECK(frame_at(plain, 1.2).V.row(far) == mid.V.row(far));
  }
  Document e;
  scratch.round_trip(d, e);
  REQUIRE(e.space_time_edits().size() == 1);
  CHECK(e.space_time_edits()[0] == d.space_time_edits()[0]);
  CHECK(frame_at(e, 1.2).V == edited.V);
  // Errors, nothing changed: brushing a dragged edit, a ball holding no vertex, no edit at all.
  REQUIRE_THROWS_WITH(run(d, "edit-brush 2 0 0\n"), Catch::Contains("has been dragged"));
  run(d, "edit-clear\n");
  REQUIRE_THROWS_WITH(run(d, "edit-brush 2 0 0\n"), Catch::Contains("start one with edit-region"));
  std::snprintf(line, sizeof line, "edit-region %.17g %.17g %.17g 0.6 0.8 2\n", hp.x(), hp.y(), hp.z());
  run(d, line);
  REQUIRE_THROWS_WITH(run(d, "edit-brush 40 40 40\n"), Catch::Contains("holds no vertex"));
  CHECK(d.space_time_edits().back().region.dabs.empty());
}

TEST_CASE("space-time edits: hostile input is a clear error and changes nothing; a stale edit is reported",
          "[script][space-time]") {
  Document d;
  make_keyed(d);
  const int depth = d.undo_depth();
  auto fails = [&](const std::string& text, const std::string& what) {
    try {
      run(d, text);
      FAIL("no error for " << text);
    } catch (const Error& err) {
      INFO(err.what());
      CHECK(std::string(err.what()).find(what) != std::string::npos);
    }
  };
  fails("edit-drag 2 0 0 0 0 1\n", "edit-region");                        // no region yet
  fails("edit-region 10 10 10 0.5 0.8 2\n", "no vertex");                 // a region with no vertex
  fails("edit-region 2 0 0 1 5 6\n", "outside the animation");            // a window outside the animation
  fails("edit-region 2 0 0 1 1 0.5\n", "T0 < T1");
  CHECK(d.undo_depth() == depth);
  run(d, "edit-region 2 0 0 1.2 0.8 2\n");
  fails("set-time 1.2\nedit-drag -2 0 0 0 0 1\n", "handle");              // a handle outside the region
  fails("set-time 0.2\nedit-drag 2 0 0 0 0 1\n", "outside the window");   // the current time outside it
  CHECK(d.undo_depth() == depth + 1);
  CHECK(d.space_time_edits().size() == 1);

  // A stored edit whose region the keys no longer reach: skipped and named, the rest of the frame built.
  SpaceTimeEdit stale = d.space_time_edits()[0];
  stale.region.center = {50, 50, 50};
  stale.handle = {{50, 50, 50}, 1.2};
  stale.move = {0, 0, 1};
  d.add_space_time_edit(stale);
  std::vector<std::string> notes;
  const AnimationManifold m = document_manifold(d, nullptr, {}, &notes);
  REQUIRE(notes.size() == 1);
  CHECK(notes[0].find("space-time edit 2 skipped") == 0);
  d.set_time(1.2);
  CHECK_NOTHROW(posed_surface(d));
}

TEST_CASE("edit-drag's retime DT: the handle's frame moves in time, the scene keeps it, a fold is refused",
          "[script][space-time]") {
  const ScratchScene scratch("retime");
  Document d;
  make_keyed(d);
  const TriMesh mid = frame_at(d, 1.0), early = frame_at(d, 0.2);
  const Eigen::Vector3d hp = mid.V.row(nearest(mid, {2.0, 0.4, 0})).transpose();
  char line[256];
  std::snprintf(line, sizeof line, "set-time 1\nedit-region %.17g %.17g %.17g 1.2 0.4 1.6\n", hp.x(), hp.y(), hp.z());
  run(d, line);
  const int depth = d.undo_depth();
  // Past the window's end (1.6) the anchors stay: the slab would fold back in time.
  try {
    std::snprintf(line, sizeof line, "edit-drag %.17g %.17g %.17g 0 0 0.3 0.9\n", hp.x(), hp.y(), hp.z());
    run(d, line);
    FAIL("a folding retime was accepted");
  } catch (const Error& err) {
    INFO(err.what());
    CHECK(std::string(err.what()).find("folds the manifold in time") != std::string::npos);
  }
  CHECK(d.undo_depth() == depth);
  {
    // The editor's retime drag asks a trial of the replay: it refuses what edit-drag refuses, takes the rest.
    SpaceTimeEdit e = d.space_time_edits()[0];
    e.handle = {hp, 1.0};
    e.move = {0, 0, 0.3};
    const SpaceTimeRetimeTrial trial(manifold_before_edit(d, 0), e);
    CHECK(trial.refusal(0.9).find("folds the manifold in time") != std::string::npos);
    CHECK(trial.refusal(0.1).empty());
    CHECK(trial.refusal(-0.1).empty());
    CHECK(trial.refusal(0).empty());
    // A window from the first layer: no retime at all (the first layer bounds the animation).
    e.region.t0 = 0;
    const SpaceTimeRetimeTrial first(manifold_before_edit(d, 0), e);
    CHECK(first.refusal(0.05).find("first or last layer") != std::string::npos);
    CHECK(first.refusal(0).empty());
  }
  std::snprintf(line, sizeof line, "edit-drag %.17g %.17g %.17g 0 0 0.3 0.1\n", hp.x(), hp.y(), hp.z());
  run(d, line);
  REQUIRE(d.space_time_edits().size() == 1);
  CHECK(d.space_time_edits()[0].retime == 0.1);
  // The handle point's frame is at t = 1.1 now, moved by the drag.
  const TriMesh later = frame_at(d, 1.1);
  const Eigen::Vector3d want = hp + Eigen::Vector3d(0, 0, 0.3);
  const double miss = (later.V.row(nearest(later, want)).transpose() - want).norm();
  INFO("nearest frame vertex at t = 1.1 to the dragged handle point: " << miss);
  CHECK(miss < 1e-9);
  CHECK(frame_at(d, 0.2).V == early.V);  // before the window: bit for bit
  // The scene keeps the retime and replays it.
  Document e;
  scratch.round_trip(d, e);
  REQUIRE(e.space_time_edits().size() == 1);
  CHECK(e.space_time_edits()[0] == d.space_time_edits()[0]);
  CHECK(frame_at(e, 1.1).V == later.V);
}

TEST_CASE("edit-region's setup words: the edit's weights, time scale and volume, kept by its drags and the scene, "
          "replayed as the editor with those options drags", "[script][space-time]") {
  const ScratchScene scratch("setup");
  Document d;
  make_keyed(d);
  const TriMesh mid = frame_at(d, 1.2);
  const Eigen::Vector3d hp = mid.V.row(nearest(mid, {2.0, 0.4, 0})).transpose();
  const int depth = d.undo_depth();
  char line[320];
  std::snprintf(line, sizeof line,
                "set-time 1.2\nedit-region %.17g %.17g %.17g 1.2 0.8 2 weights=dual time-scale=4 volume\n"
                "edit-drag %.17g %.17g %.17g 0 0 0.5\n",
                hp.x(), hp.y(), hp.z(), hp.x(), hp.y(), hp.z());
  run(d, line);
  REQUIRE(d.space_time_edits().size() == 1);
  const SpaceTimeEdit e = d.space_time_edits()[0];
  CHECK(e.weights == LaplacianWeights::Dual);
  CHECK(e.time_scale == 4);
  CHECK(e.preserve_volume);
  CHECK(d.undo_depth() == depth + 2);

  // The replay is ManifoldEditor with those options on the keys' manifold (what edit-manifold runs),
  // bit for bit; the default options give another manifold (the words are used, not only stored).
  Document keys_only;
  make_keyed(keys_only);
  const AnimationManifold keys_m = document_manifold(keys_only);
  auto dragged = [&](const ManifoldEditOptions& o) {
    ManifoldEditor ed(keys_m, select_edit_region(keys_m, e.region, e.handle), e.handle.point, o);
    ManifoldDrag drag;
    drag.translation = e.move;
    return ed.drag(drag);
  };
  ManifoldEditOptions o;
  o.weights = LaplacianWeights::Dual;
  o.time_scale = 4;
  o.preserve_volume = true;
  std::vector<std::string> notes;
  const AnimationManifold edited = document_manifold(d, nullptr, {}, &notes);
  CHECK(notes.empty());
  CHECK(edited.V == dragged(o));
  CHECK((edited.V - dragged(ManifoldEditOptions{})).cwiseAbs().maxCoeff() > 1e-3);

  // Another handle appends an edit over the same region with the same setup.
  std::snprintf(line, sizeof line, "set-time 1.6\nedit-drag %.17g %.17g %.17g 0 0.1 0\n", hp.x(), hp.y(), hp.z());
  run(d, line);
  REQUIRE(d.space_time_edits().size() == 2);
  const SpaceTimeEdit& e2 = d.space_time_edits()[1];
  CHECK((e2.weights == e.weights && e2.time_scale == e.time_scale && e2.preserve_volume == e.preserve_volume));
  CHECK(d.space_time_edits()[1].handle.time == 1.6);

  // The scene keeps the setup of both.
  Document l;
  scratch.round_trip(d, l);
  CHECK(l.space_time_edits() == d.space_time_edits());
  CHECK(frame_at(l, 1.2).V == frame_at(d, 1.2).V);

  // Undo: the second edit, its press... back to no edit.
  run(d, "undo\nundo\nundo\n");
  CHECK(d.space_time_edits().empty());
  CHECK(d.undo_depth() == depth);
}

TEST_CASE("edit-region's setup words: a bad word is an error naming it, nothing changed", "[script][space-time]") {
  Document d;
  make_keyed(d);
  run(d, "edit-region 2 0 0 1.2 0.8 2 time-scale=0.5\n");  // a good edit first: the bad lines leave it
  REQUIRE(d.space_time_edits().size() == 1);
  CHECK(d.space_time_edits()[0].time_scale == 0.5);
  const std::vector<SpaceTimeEdit> before = d.space_time_edits();
  const int depth = d.undo_depth();
  const std::uint64_t revision = d.revision();
  auto fails = [&](const std::vector<std::string>& extra, const std::string& what) {
    CommandWords w = command_words("edit-region", {2.0, 0.0, 0.0, 1.2, 0.8, 2.0});
    w.insert(w.end(), extra.begin(), extra.end());
    try {
      run_command(d, w);  // the UI's path: check_command, then the run
      FAIL("no error for " << w.back());
    } catch (const Error& err) {
      INFO(err.what());
      CHECK(std::string(err.what()).find("edit-region: ") == 0);
      CHECK(std::string(err.what()).find(what) != std::string::npos);
    }
  };
  fails({"weights=cotan"}, "weights=: unknown Laplacian weights 'cotan'");
  fails({"weights="}, "weights=: unknown Laplacian weights ''");
  fails({"time-scale=0"}, "time-scale= must be a number > 0, got '0'");
  fails({"time-scale=-2"}, "time-scale= must be a number > 0, got '-2'");
  fails({"time-scale=fast"}, "time-scale= must be a number > 0, got 'fast'");
  fails({"time-scale=inf"}, "time-scale= must be a number > 0, got 'inf'");
  fails({"volumes"}, "unknown word 'volumes' (weights=W, time-scale=S, volume)");
  fails({"volume", "volume"}, "volume given twice");
  fails({"weights=dual", "weights=equal"}, "weights= given twice");
  fails({"time-scale=2", "volume", "time-scale=3"}, "time-scale= given twice");
  fails({"volume", "weights=dual", "time-scale=2", "volume"}, "takes 6..9 argument(s)");
  // The words are checked before the region: a bad word on a line with a bad region names the word.
  try {
    run(d, "edit-region 50 50 50 1 0.8 2 weights=dual vol\n");
    FAIL("no error");
  } catch (const Error& err) {
    CHECK(std::string(err.what()).find("unknown word 'vol'") != std::string::npos);
  }
  CHECK(d.space_time_edits() == before);
  CHECK(d.undo_depth() == depth);
  CHECK(d.revision() == revision);
  // The good words in any order.
  run(d, "edit-region 2 0 0 1.2 0.8 2 volume time-scale=3 weights=primal-boundary\n");
  REQUIRE(d.space_time_edits().size() == 2);
  const SpaceTimeEdit& e = d.space_time_edits()[1];
  CHECK(e.weights == LaplacianWeights::PrimalBoundary);
  CHECK(e.time_scale == 3);
  CHECK(e.preserve_volume);
}

TEST_CASE("a drag's frames through the cache: only the regions' rows written, the normals bit for bit, the same as "
          "a replay without it", "[script][space-time]") {
  Document d;
  make_keyed(d);
  const AnimationManifold base = document_manifold(d);
  const Eigen::MatrixXd base_normals = manifold_vertex_normals(base);
  const TriMesh mid = frame_at(d, 1.0);
  auto edit_at = [&](const Eigen::Vector3d& p, double radius) {
    SpaceTimeEdit e;
    e.region = {mid.V.row(nearest(mid, p)).transpose(), radius, 0.4, 1.6};
    e.handle = {e.region.center, 1.0};
    return e;
  };
  std::vector<SpaceTimeEdit> edits = {edit_at({2.0, 0.4, 0}, 1.2)};
  // Frames: a drag, a retime (new slabs: the plan is not used), a second edit elsewhere, a turn.
  SpaceTimeEditCache cache;
  AnimationManifold buffers[2] = {base, base};  // the builder's two in turn
  Eigen::MatrixXd normals[2];
  bool reusable[2] = {true, true};
  for (int f = 0; f < 12; ++f) {
    edits[0].move = Eigen::Vector3d(0.02 * f, 0.3 - 0.01 * f, 0.05);
    if (f == 4) edits.push_back(edit_at({-2.0, 0, 0}, 0.8)), edits[1].move = {0, 0.2, 0};
    edits[0].retime = f == 2 ? 0.1 : 0.0;
    if (f == 9) edits[1].rotation = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitX());
    INFO("frame " << f);
    AnimationManifold& m = buffers[f % 2];
    if (reusable[f % 2])
      m.V = base.V;
    else
      m = base;
    const auto notes = apply_space_time_edits(m, edits, &cache);
    INFO((notes.empty() ? "" : notes[0]));
    REQUIRE(notes.empty());
    reusable[f % 2] = cache.written_valid;
    AnimationManifold fresh = base;
    apply_space_time_edits(fresh, edits);
    CHECK(m.V == fresh.V);
    CHECK(m.T == fresh.T);
    CHECK(cache.written_valid == (f != 2));
    if (cache.written_valid) {
      std::vector<char> written(base.num_vertices(), 0);
      for (int v : cache.written) written[v] = 1;
      int moved_outside = 0, moved = 0;
      for (int v = 0; v < base.num_vertices(); ++v)
        (written[v] ? moved : moved_outside) += m.V.row(v) != base.V.row(v);
      CHECK(moved_outside == 0);
      CHECK(moved > 0);
    }
    edited_vertex_normals(m, base.V, base_normals, edits, cache, normals[f % 2]);
    CHECK(normals[f % 2] == manifold_vertex_normals(m));
  }
}
