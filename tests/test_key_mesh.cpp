// Mesh keys: Document::key_mesh is one undoable step that replaces a key at the same time; bad files
// (missing, open, NaN) are errors naming the file that leave the document unchanged; the script's
// key-mesh; key_surfaces / document_manifold give exactly the prism build for same-connectivity keys,
// and (with a transition) a closed slice between a sphere and a torus.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <Eigen/Geometry>

#include "core/anim/bake.h"
#include "core/anim/manifold.h"
#include "core/anim/manifold_frame.h"
#include "core/anim/manifold_io.h"
#include "core/anim/surface_checks.h"
#include "core/mesh/io.h"
#include "core/scene/key_surfaces.h"
#include "core/scene/script.h"
#include "core/util/error.h"
#include "tests/key_mesh_test_meshes.h"

using namespace dfm;
namespace fs = std::filesystem;

namespace {

struct TempDir {
  fs::path dir = fs::temp_directory_path() / ("dfm_key_mesh_test_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(dir); }
  ~TempDir() { fs::remove_all(dir); }
  std::string operator/(const std::string& f) const { return (dir / f).string(); }
};

TriMesh sphere(double r = 1.0) { return test::icosphere({0, 0, 0}, r, 1); }

// Point handles on an icosphere, weights fixed by hand (vertex i follows handle 0 by w0(i)).
void make_posable(Document& d) {
  d.set_surface(sphere(), "sphere");
  d.add_point({0.1, 0.1, 0.1});
  d.add_point({-0.1, 0.0, 0.0});
  const int n = d.surface().num_vertices();
  Eigen::MatrixXd W(n, 2);
  for (int i = 0; i < n; ++i) {
    const double w = 0.5 + 0.5 * d.surface().V(i, 0);
    W.row(i) << w, 1 - w;
  }
  d.set_weights(W, {});
}

// Every edit that could have happened is absent: same keys, same undo depth, same revision.
struct Snapshot {
  size_t keys;
  int depth;
  std::uint64_t revision;
  explicit Snapshot(const Document& d) : keys(d.keys().size()), depth(d.undo_depth()), revision(d.revision()) {}
  bool same(const Document& d) const {
    return keys == d.keys().size() && depth == d.undo_depth() && revision == d.revision();
  }
};

}  // namespace

// Bit-identical manifolds: vertices, tetrahedra, layer times and slabs.
static void check_same_manifold(const AnimationManifold& got, const AnimationManifold& want) {
  CHECK(got.V == want.V);
  CHECK(got.T == want.T);
  CHECK(got.times == want.times);
  CHECK(got.slab_offsets == want.slab_offsets);
}

TEST_CASE("key_mesh is one undo step, replaces a key at the same time, and undoes exactly") {
  Document d;
  make_posable(d);
  d.set_key(0);
  const TriMesh t = test::torus({0, 0, 0}, 1, 0.4, 12, 8);
  d.key_mesh(t, "torus.obj", 1);
  REQUIRE(d.keys().size() == 2);
  CHECK_FALSE(d.keys()[0].is_mesh());
  CHECK(d.keys()[1].is_mesh());
  CHECK(d.keys()[1].mesh_path == "torus.obj");
  CHECK(d.keys()[1].mesh.V == t.V);
  CHECK(d.keys()[1].mesh.F == t.F);
  CHECK(d.keys()[1].params.point_translation.size() == 2);  // sized to the rig like every key
  CHECK(d.has_mesh_keys());
  CHECK(d.undo_name() == "key mesh torus.obj");

  // Replace the pose key at 0 with a mesh, then back with a pose key; undo walks back exactly.
  d.key_mesh(sphere(0.5), "small.obj", 0);
  REQUIRE(d.keys().size() == 2);
  CHECK(d.keys()[0].is_mesh());
  d.set_key(0);
  CHECK_FALSE(d.keys()[0].is_mesh());
  CHECK(d.keys()[0].mesh_path.empty());
  d.undo();
  CHECK(d.keys()[0].mesh_path == "small.obj");
  d.undo();
  CHECK_FALSE(d.keys()[0].is_mesh());
  d.undo();
  REQUIRE(d.keys().size() == 1);
  CHECK_FALSE(d.has_mesh_keys());
  d.redo();
  REQUIRE(d.keys().size() == 2);
  CHECK(d.keys()[1].mesh.V == t.V);
  // A mesh key moves like any key; it has no pose to go to.
  d.move_key(1, 2.5);
  CHECK(d.keys()[1].time == 2.5);
  CHECK_THROWS_WITH(d.go_to_key(1), Catch::Contains("mesh key") && Catch::Contains("torus.obj"));
  // Rig edits keep the mesh and refit the params.
  d.add_point({0, 0, 0.2});
  CHECK(d.keys()[1].is_mesh());
  CHECK(d.keys()[1].params.point_translation.size() == 3);
}

TEST_CASE("hostile mesh keys give an error naming the file and leave the document unchanged") {
  TempDir tmp;
  Document d;
  make_posable(d);
  d.set_key(0);
  const Snapshot before(d);
  auto expect_refused = [&](const std::string& path, const std::string& what) {
    try {
      d.key_mesh_file(path, 1);
      FAIL("no error for " << path);
    } catch (const Error& e) {
      INFO(e.what());
      CHECK(std::string(e.what()).find(path) != std::string::npos);
      CHECK(std::string(e.what()).find(what) != std::string::npos);
    }
    CHECK(before.same(d));
  };
  expect_refused(tmp / "missing.obj", "");
  test::write_obj_raw(tmp / "open.obj", test::open_copy(sphere()));
  expect_refused(tmp / "open.obj", "");
  TriMesh nan = sphere();
  nan.V(3, 1) = std::nan("");
  test::write_obj_raw(tmp / "nan.obj", nan);
  expect_refused(tmp / "nan.obj", "");
  std::ofstream(tmp / "empty.obj") << "";
  expect_refused(tmp / "empty.obj", "");
  std::ofstream(tmp / "points.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  expect_refused(tmp / "points.obj", "");
  // In memory: bad indices and a non-finite time.
  TriMesh bad = sphere();
  bad.F(0, 0) = 999;
  CHECK_THROWS_WITH(d.key_mesh(bad, "bad.obj", 1), Catch::Contains("bad.obj"));
  CHECK_THROWS(d.key_mesh(sphere(), "s.obj", std::nan("")));
  CHECK(before.same(d));
}

TEST_CASE("script key-mesh: parsing, errors naming the line and the file, and the document unchanged") {
  TempDir tmp;
  CHECK_THROWS_WITH(parse_script("key-mesh\n", "s.txt"), Catch::Contains("s.txt:1:") && Catch::Contains("key-mesh FILE [TIME]"));
  CHECK_THROWS_WITH(parse_script("set-time 0\nkey-mesh a.obj x\n", "s.txt"),
                    Catch::Contains("s.txt:2:") && Catch::Contains("'x' is not a finite number"));
  CHECK_THROWS_WITH(parse_script("key-mesh a.obj 1 2\n", "s.txt"), Catch::Contains("takes 1..2"));
  Document d;
  make_posable(d);
  const Snapshot before(d);
  const std::string missing = tmp / "nosuch.obj";
  CHECK_THROWS_WITH(run_script(d, parse_script("key-mesh " + missing + " 1\n", "s.txt"), "s.txt"),
                    Catch::StartsWith("s.txt:1: key-mesh: " + missing));
  test::write_obj_raw(tmp / "open.obj", test::open_copy(sphere()));
  CHECK_THROWS_WITH(run_script(d, parse_script("\nkey-mesh " + tmp / "open.obj\n", "s.txt"), "s.txt"),
                    Catch::StartsWith("s.txt:2: key-mesh: " + tmp / "open.obj"));
  CHECK(before.same(d));
  // Good files key at T, or at the current time.
  write_surface(tmp / "a.obj", sphere(0.8));
  write_surface(tmp / "b.off", sphere(1.2));
  run_script(d, parse_script("key-mesh " + tmp / "a.obj" + " 2\nset-time 3\nkey-mesh " + tmp / "b.off\n", "s.txt"), "s.txt");
  REQUIRE(d.keys().size() == 2);
  CHECK(d.keys()[0].time == 2);
  CHECK(d.keys()[1].time == 3);
  CHECK(d.keys()[1].mesh_path == tmp / "b.off");
  run_script(d, parse_script("undo\n", "s.txt"), "s.txt");
  CHECK(d.keys().size() == 1);
}

TEST_CASE("pose keys only: document_manifold is the keys' poses interpolated, skinned and joined by prisms") {
  Document d;
  make_posable(d);
  d.set_inbetweens(3);
  d.set_key(0);
  d.translate_handle(0, {0.5, 0, 0});
  d.set_key(1);
  d.rotate_handle(1, Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ())));
  d.set_key(2.5);
  // Closed form of the animation: handle 0 slides to +0.5 x over [0, 1]; handle 1 then turns about
  // itself (-0.1, 0, 0), by 0.7 rad about z over [1, 2.5]. Layers at the keys and 3 in-betweens each.
  const Eigen::Vector3d p1(-0.1, 0, 0);
  const Eigen::MatrixXd& W = d.weights();
  const TriMesh& rest = d.surface();
  auto layer = [&](double t) {
    const double slide = 0.5 * std::min(t, 1.0), turn = 0.7 * std::max(0.0, (t - 1.0) / 1.5);
    const Eigen::Affine3d R =
        Eigen::Translation3d(p1) * Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ()) * Eigen::Translation3d(-p1);
    Eigen::MatrixXd P(rest.num_vertices(), 3);
    for (int i = 0; i < rest.num_vertices(); ++i) {
      const Eigen::Vector3d v = rest.V.row(i).transpose();
      P.row(i) = (W(i, 0) * (v + Eigen::Vector3d(slide, 0, 0)) + W(i, 1) * (R * v)).transpose();
    }
    return P;
  };
  std::vector<double> times;
  std::vector<Eigen::MatrixXd> layers;
  for (double t : {0.0, 0.25, 0.5, 0.75, 1.0, 1.375, 1.75, 2.125, 2.5}) {
    times.push_back(t);
    layers.push_back(layer(t));
  }
  const AnimationManifold want = build_manifold(layers, rest.F, times);
  SequenceStats st;
  const AnimationManifold got = document_manifold(d, &st);
  REQUIRE(got.V.rows() == want.V.rows());
  CHECK((got.V - want.V).cwiseAbs().maxCoeff() < 1e-12);
  CHECK(got.T == want.T);
  CHECK(got.times == want.times);
  CHECK(got.slab_offsets == want.slab_offsets);
  CHECK(st.prism_slabs == 8);
  CHECK(st.transition_slabs == 0);
  CHECK_FALSE(needs_transition(key_surfaces(d)));
}

TEST_CASE("same-connectivity mesh keys give exactly the prism build, mixed with pose keys too") {
  Document d;
  make_posable(d);
  const TriMesh s = sphere();
  TriMesh moved = s, grown = s;
  moved.V.col(0).array() += 0.3;
  grown.V *= 1.4;
  d.key_mesh(s, "s.obj", 0);
  d.key_mesh(moved, "moved.obj", 1);
  d.key_mesh(grown, "grown.obj", 2);
  const std::vector<KeySurface> keys = key_surfaces(d);
  REQUIRE(keys.size() == 3);
  CHECK(keys[1].name == "moved.obj");
  CHECK_FALSE(needs_transition(keys));
  SequenceStats st;
  const AnimationManifold got = document_manifold(d, &st);
  const AnimationManifold want = build_manifold({s.V, moved.V, grown.V}, s.F, {0, 1, 2});
  check_same_manifold(got, want);
  CHECK(st.prism_slabs == 2);
  CHECK(st.transition_slabs == 0);

  // A pose key (the rest pose, skinned) at 3 with in-betweens: only between pose keys, so none here.
  d.set_key(3);
  const Eigen::MatrixXd rest = skin(d.method(), make_skin_binding(d.surface().V, {}, d.weights(), d.rig(), 0),
                                    d.pose(), {}).V;
  const AnimationManifold mixed = document_manifold(d);
  const AnimationManifold want2 = build_manifold({s.V, moved.V, grown.V, rest}, s.F, {0, 1, 2, 3});
  CHECK(mixed.V == want2.V);
  CHECK(mixed.T == want2.T);
  // save-posed slices it, and needs no transition.
  d.set_time(2.5);
  const TriMesh slice = posed_surface(d);
  CHECK(is_closed_and_oriented(slice.F));
}

TEST_CASE("pose keys without weights: a clear error, mesh keys alone need none") {
  Document d;
  d.set_surface(sphere(), "sphere");
  d.set_key(0);
  d.key_mesh(sphere(1.5), "big.obj", 1);
  CHECK_THROWS_WITH(document_manifold(d), Catch::Contains("pose keys need weights"));
  d.delete_key(0);
  d.key_mesh(sphere(0.5), "small.obj", 0);
  d.set_time(0.5);
  const TriMesh m = posed_surface(d);  // two same-connectivity meshes: no bind needed
  CHECK(is_closed_and_oriented(m.F));
  CHECK(enclosed_volume(m.V, m.F) > 0);
  d.delete_key(1);
  CHECK(posed_surface(d).V == sphere(0.5).V);  // one mesh key: that mesh
}

TEST_CASE("a transition: sphere key at 0, torus key-mesh at 1, the slice at 0.5 is closed", "[transition]") {
  TempDir tmp;
  write_surface(tmp / "sphere.obj", sphere());
  write_surface(tmp / "torus.obj", test::torus({0, 0, 0}, 1.0, 0.35, 16, 8));
  Document d;
  const std::string out = tmp / "mid.obj";
  run_script(d,
             parse_script("key-mesh " + tmp / "sphere.obj" + " 0\nkey-mesh " + tmp / "torus.obj" +
                              " 1\nset-time 0.5\nsave-posed " + out + "\n",
                          "s.txt"),
             "s.txt");
  CHECK(needs_transition(key_surfaces(d)));
  const TriMesh mid = read_surface(out);
  REQUIRE(mid.num_faces() > 0);
  CHECK(is_closed_and_oriented(mid.F));
  CHECK(enclosed_volume(mid.V, mid.F) > 0);
  SequenceStats st;
  document_manifold(d, &st);
  CHECK(st.transition_slabs == 1);
  CHECK(st.prism_slabs == 0);

  // A torus moved by (0, 0, 1) keyed at 2: the transition is followed by a prism slab, whose frames
  // are the torus mesh (its layers renumbered after the transition's vertices), while the transition's
  // frames stay its slices.
  TriMesh moved = test::torus({0, 0, 0}, 1.0, 0.35, 16, 8);
  const TriMesh torus = moved;
  moved.V.col(2).array() += 1.0;
  write_surface(tmp / "moved.obj", moved);
  run_script(d, parse_script("key-mesh " + tmp / "moved.obj" + " 2\n", "s.txt"), "s.txt");
  const AnimationManifold M = document_manifold(d, &st);
  CHECK(st.transition_slabs == 1);
  CHECK(st.prism_slabs == 1);
  REQUIRE(M.prism_slabs.size() == static_cast<size_t>(M.num_slabs()));
  CHECK(prism_slab_at(M, 0.5) == -1);
  CHECK(prism_slab_at(M, 1.0) == M.num_slabs() - 1);  // the torus key: its prism layer
  const ManifoldSlice f = manifold_frame(M, 1.25);
  REQUIRE(f.mesh.F == torus.F);
  Eigen::MatrixXd expect = torus.V;
  expect.col(2).array() += 0.25;
  CHECK((f.mesh.V - expect).cwiseAbs().maxCoeff() < 1e-12);
  const ManifoldSlice key = manifold_frame(M, 1.0);
  CHECK(key.mesh.V == torus.V);  // a layer's time: that layer, bit for bit
  const ManifoldSlice tr = manifold_frame(M, 0.5), exact = slice_manifold(M, SliceAxis::T, 0.5);
  CHECK(tr.mesh.V == exact.mesh.V);
  CHECK(tr.mesh.F == exact.mesh.F);
  // At the sphere's time the frame is the sphere itself: its vertices in its order, its triangles, none
  // of the transition's surface Steiner points the slice there has; saved frames at the ends too.
  const TriMesh ball = sphere();
  REQUIRE(key_layer_at(M, 0.0) >= 0);
  const ManifoldSlice first = manifold_frame(M, 0.0);
  CHECK(first.mesh.F == ball.F);
  REQUIRE(first.mesh.num_vertices() == ball.num_vertices());
  CHECK((first.mesh.V - ball.V).cwiseAbs().maxCoeff() < 1e-12);
  CHECK(slice_manifold(M, SliceAxis::T, 0.0).mesh.num_vertices() >= ball.num_vertices());
  for (int v = 0; v < first.mesh.num_vertices(); ++v) CHECK(first.mesh.N.row(v).dot(ball.V.row(v)) > 0.8);  // outward
  run_script(d, parse_script("save-frames " + tmp / "f" + " 5\n", "s.txt"), "s.txt");
  CHECK(read_surface(tmp / "f0000.obj").num_vertices() == ball.num_vertices());
  CHECK(read_surface(tmp / "f0004.obj").num_vertices() == moved.num_vertices());
  CHECK(read_surface(tmp / "f0002.obj").F == torus.F);  // t = 1: the torus key, within the prism run
  // The key layers survive a .tet4 round trip.
  write_manifold(tmp / "m.tet4", M);
  const AnimationManifold R = read_manifold(tmp / "m.tet4");
  REQUIRE(R.key_layers.size() == M.key_layers.size());
  CHECK(manifold_frame(R, 0.0).mesh.V == first.mesh.V);
}

TEST_CASE("in-betweens per key interval: ARAP turns a body rigidly, linear shrinks it, handles add none "
          "between mesh keys; undo, scene files and the script") {
  // An elongated closed body and the same body turned by 120 degrees about z and moved.
  TriMesh k0 = test::icosphere({0, 0, 0}, 1.0, 2);
  k0.V.col(0) *= 3.0;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(2 * M_PI / 3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  TriMesh k1 = k0;
  k1.V = (k0.V * R.transpose()).rowwise() + Eigen::RowVector3d(0.5, -0.2, 0.1);
  Document d;
  d.set_surface(k0, "body");
  d.key_mesh(k0, "k0.obj", 0.0);
  d.key_mesh(k1, "k1.obj", 1.0);
  d.set_inbetweens(1);
  CHECK(key_surfaces(d).size() == 2);  // handles between mesh keys: the prism's own blend, no layer

  d.set_key_inbetween(0, InbetweenMethod::Arap);
  std::vector<KeySurface> s = key_surfaces(d);
  REQUIRE(s.size() == 3);
  CHECK(s[1].time == 0.5);
  CHECK(s[0].V == k0.V);
  CHECK(s[2].V == k1.V);
  // Halfway: the body turned by 60 degrees, up to a translation (Alexa 2002, 4.4).
  const Eigen::Matrix3d R60 = Eigen::AngleAxisd(M_PI / 3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::MatrixXd expect = k0.V * R60.transpose();
  const Eigen::RowVector3d shift = (s[1].V - expect).colwise().mean();
  const double diag = (k0.V.colwise().maxCoeff() - k0.V.colwise().minCoeff()).norm();
  CHECK(((s[1].V - expect).rowwise() - shift).cwiseAbs().maxCoeff() < 1e-6 * diag);

  d.set_key_inbetween(0, InbetweenMethod::Linear);
  s = key_surfaces(d);
  REQUIRE(s.size() == 3);
  CHECK(s[1].V == 0.5 * k0.V + 0.5 * k1.V);
  CHECK(enclosed_volume(s[1].V, s[1].F) < 0.5 * enclosed_volume(k0.V, k0.F));  // the linear blend shrinks it

  d.undo();
  CHECK(d.keys()[0].inbetween == InbetweenMethod::Arap);
  TempDir tmp;
  d.save_scene(tmp / "ib.scene.json");
  Document e;
  e.load_scene(tmp / "ib.scene.json");
  CHECK(e.keys()[0].inbetween == InbetweenMethod::Arap);
  CHECK(e.keys()[1].inbetween == InbetweenMethod::Handles);

  // The script's set-inbetween is the same command.
  run_script(e, parse_script("set-inbetween 0 linear\n", "s.txt"), "s.txt");
  CHECK(e.keys()[0].inbetween == InbetweenMethod::Linear);
  CHECK_THROWS_WITH(parse_script("set-inbetween 0 spline\n", "s.txt"), Catch::Contains("s.txt:1:") && Catch::Contains("spline"));
  CHECK_THROWS_WITH(run_script(e, parse_script("set-inbetween 0.3 arap\n", "s.txt"), "s.txt"), Catch::Contains("no key at time 0.3"));
}
