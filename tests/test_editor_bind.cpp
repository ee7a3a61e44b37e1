// The editor's bind: the worker job runs the same core call as scripts and `deform bind`
// (bind_surface with bind_options(doc)), so its weights equal run_bind_blocking's exactly, the painted
// shape-preservation mask reaches the solver (and changes the weights), progress is monotone and
// Cancel stops it. The mask's mapping from surface vertices to bind-volume tets is checked by hand.
#include <catch2/catch.hpp>

#include <array>
#include <chrono>
#include <map>
#include <thread>

#include "app/editor/bind_worker.h"
#include "core/bind/bind.h"
#include "core/scene/bind_document.h"
#include "core/util/error.h"

using namespace dfm;

namespace {

// Closed box [0,2]x[0,1]x[0,1], each unit of each face split into n x n quads (outward triangles).
TriMesh box_surface(int n) {
  std::map<std::array<int, 3>, int> index;
  std::vector<Eigen::Vector3d> V;
  std::vector<Eigen::Vector3i> F;
  const int size[3] = {2 * n, n, n};
  auto vid = [&](std::array<int, 3> g) {
    auto it = index.find(g);
    if (it != index.end()) return it->second;
    V.emplace_back(double(g[0]) / n, double(g[1]) / n, double(g[2]) / n);
    return index[g] = int(V.size()) - 1;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (int i = 0; i < size[u]; ++i)
        for (int j = 0; j < size[v]; ++j) {
          std::array<int, 3> c[4];
          for (int k = 0; k < 4; ++k) {
            c[k][axis] = side ? size[axis] : 0;
            c[k][u] = i + (k == 1 || k == 2);
            c[k][v] = j + (k >= 2);
          }
          const int a = vid(c[0]), b = vid(c[1]), cc = vid(c[2]), d = vid(c[3]);
          // (u, v, axis) is right-handed: u x v = +axis, so side 1 keeps the order, side 0 flips it.
          if (side) F.emplace_back(a, b, cc), F.emplace_back(a, cc, d);
          else F.emplace_back(a, cc, b), F.emplace_back(a, d, cc);
        }
    }
  TriMesh m;
  m.V.resize(V.size(), 3);
  for (size_t i = 0; i < V.size(); ++i) m.V.row(i) = V[i].transpose();
  m.F.resize(F.size(), 3);
  for (size_t i = 0; i < F.size(); ++i) m.F.row(i) = F[i].transpose();
  return m;
}

void make_bindable(Document& d) {
  d.set_surface(box_surface(3), "box");
  d.add_point({0.3, 0.5, 0.5});
  d.add_point({1.7, 0.5, 0.5});
}

// Paints every surface vertex in the middle third of the box (x in [2/3, 4/3]) fully.
void paint_middle(Document& d) {
  std::vector<int> verts;
  std::vector<double> vals;
  for (int i = 0; i < d.surface().num_vertices(); ++i)
    if (d.surface().V(i, 0) > 0.6 && d.surface().V(i, 0) < 1.4) verts.push_back(i), vals.push_back(1.0);
  d.paint_mask(verts, vals);
}

editor::BindOutcome run_job(const Document& d, std::vector<std::pair<std::string, double>>* progress = nullptr,
                    bool cancel_at_start = false) {
  editor::BindWorker w;
  REQUIRE(w.start(editor::make_document_bind_job(d)));
  if (cancel_at_start) w.cancel();
  while (w.running()) {
    if (progress) {
      const editor::BindProgress p = w.progress();
      if (progress->empty() || progress->back().first != p.stage || progress->back().second != p.fraction)
        progress->push_back({p.stage, p.fraction});
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  auto r = w.take_result();
  REQUIRE(r.has_value());
  return *r;
}

}  // namespace

TEST_CASE("painted mask: surface vertices -> per-tet rho of the bind volume", "[editor][bind]") {
  BindVolume vol;
  vol.tets.V.resize(5, 3);
  vol.tets.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1;
  vol.tets.T.resize(2, 4);
  vol.tets.T << 0, 1, 2, 3, 1, 2, 3, 4;
  // User vertex 0 is tet vertex 0; user vertex 1 sits halfway between tet vertices 3 and 4.
  vol.to_user.resize(2, 5);
  std::vector<Eigen::Triplet<double>> t{{0, 0, 1.0}, {1, 3, 0.5}, {1, 4, 0.5}};
  vol.to_user.setFromTriplets(t.begin(), t.end());
  Eigen::VectorXd m(2);
  m << 8.0, 4.0;
  const Eigen::VectorXd rho = tet_mask_from_user_vertices(vol, m);
  REQUIRE(rho.size() == 2);
  CHECK(rho[0] == Approx((8.0 + 0 + 0 + 4.0) / 4));  // vertices 0 (8) and 3 (4)
  CHECK(rho[1] == Approx((0 + 0 + 4.0 + 4.0) / 4));  // vertices 3 and 4 (4 each)
  CHECK_THROWS_WITH(tet_mask_from_user_vertices(vol, Eigen::VectorXd::Ones(3)), Catch::Contains("3 values for 2"));
}

TEST_CASE("bind_options carries the painted mask of a surface document", "[editor][bind]") {
  Document d;
  make_bindable(d);
  BindOptions o = bind_options(d);
  CHECK(o.vertex_mask.size() == 0);
  CHECK(o.bbw.shape_mask.size() == 0);
  paint_middle(d);
  o = bind_options(d);
  REQUIRE(o.vertex_mask.size() == d.surface().num_vertices());
  CHECK(o.bbw.shape_mask.size() == 0);  // the TetGen volume does not exist yet
  CHECK((o.vertex_mask - kPaintedMaskRho * d.mask()).cwiseAbs().maxCoeff() == 0.0);
}

TEST_CASE("the editor's bind job equals the script/CLI bind, mask included", "[editor][bind]") {
  Document plain, painted, reference;
  make_bindable(plain);
  make_bindable(painted);
  make_bindable(reference);
  paint_middle(painted);
  paint_middle(reference);

  std::vector<std::pair<std::string, double>> progress;
  const editor::BindOutcome a = run_job(painted, &progress);
  INFO(a.error);
  REQUIRE(a.ok);
  apply_bind_result(painted, *a.result);
  run_bind_blocking(reference);
  REQUIRE(painted.weights().rows() == reference.weights().rows());
  CHECK((painted.weights() - reference.weights()).cwiseAbs().maxCoeff() == 0.0);

  const editor::BindOutcome b = run_job(plain);
  REQUIRE(b.ok);
  apply_bind_result(plain, *b.result);
  // The mask stiffens the middle: the weights there differ from the unpainted bind's.
  const double diff = (painted.weights() - plain.weights()).cwiseAbs().maxCoeff();
  INFO("max weight change from the mask " << diff);
  CHECK(diff > 1e-3);

  REQUIRE(!progress.empty());
  for (size_t k = 1; k < progress.size(); ++k) CHECK(progress[k].second >= progress[k - 1].second);
  CHECK(progress.front().second < 0.5);
}

TEST_CASE("the editor's bind job: cancel stops it, a rig edit refuses the stale result", "[editor][bind]") {
  Document d;
  make_bindable(d);
  const editor::BindOutcome c = run_job(d, nullptr, true);
  CHECK(!c.ok);
  CHECK(c.cancelled);
  CHECK(c.error == "bind cancelled");

  const editor::BindOutcome r = run_job(d);
  REQUIRE(r.ok);
  d.add_point({1.0, 0.5, 0.5});  // the rig changed while the bind ran
  CHECK_THROWS_AS(apply_bind_result(d, *r.result), Error);
  CHECK_THROWS_WITH(editor::make_document_bind_job(Document{}), Catch::Contains("open a mesh first"));
}
