// Space-time Laplacian editing of animation manifolds (Southern 2008, 4.2-4.4; issue 35):
// core/anim/manifold_edit_region.h, manifold_laplacian.h, manifold_edit.h, manifold_edit_volume.h.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <catch2/catch.hpp>
#include <Eigen/Geometry>

#include "core/anim/manifold.h"
#include "core/anim/manifold_edit.h"
#include "core/anim/manifold_edit_region.h"
#include "core/anim/manifold_laplacian.h"
#include "core/anim/primal_boundary_weights.h"
#include "core/anim/slice.h"
#include "core/mesh/io.h"
#include "core/util/error.h"
#include "tests/test_support.h"

using namespace dfm;

namespace {

double smoothstep(double u) {
  u = std::clamp(u, 0.0, 1.0);
  return u * u * (3 - 2 * u);
}

// The arm bent at the elbow by `degrees` about z: vertices past the elbow turn by a smoothstep of their
// distance along the arm (a skin-like blend over 0.2 units), the rest stay.
Eigen::MatrixXd bent_arm(const Eigen::MatrixXd& V, double degrees) {
  const Eigen::Vector3d elbow(0.081400687, 0.18519857, -0.042544638);  // arm.tgf joint 3
  Eigen::MatrixXd out = V;
  for (int i = 0; i < V.rows(); ++i) {
    const double w = smoothstep((V(i, 0) - elbow.x() + 0.1) / 0.2);
    const Eigen::Matrix3d R = Eigen::AngleAxisd(w * degrees * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    out.row(i) = (R * (V.row(i).transpose() - elbow) + elbow).transpose();
  }
  return out;
}

// What `deform manifold --keyframes K0 K1 K2 --inbetween linear --inbetweens N` builds: keys at t = 0, 1, 2
// and N linearly blended layers between neighbours, joined by the prism build.
AnimationManifold keyed_manifold(const std::vector<Eigen::MatrixXd>& keys, const Eigen::MatrixXi& F, int inbetweens) {
  std::vector<Eigen::MatrixXd> layers;
  std::vector<double> times;
  for (size_t k = 0; k + 1 < keys.size(); ++k)
    for (int i = 0; i <= inbetweens; ++i) {
      const double u = double(i) / (inbetweens + 1);
      layers.push_back((1 - u) * keys[k] + u * keys[k + 1]);
      times.push_back(k + u);
    }
  layers.push_back(keys.back());
  times.push_back(double(keys.size() - 1));
  return build_manifold(layers, F, times);
}

double mesh_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  double v = 0;
  for (int f = 0; f < F.rows(); ++f)
    v += Eigen::Vector3d(V.row(F(f, 0))).dot(Eigen::Vector3d(V.row(F(f, 1))).cross(Eigen::Vector3d(V.row(F(f, 2)))));
  return v / 6;
}

// Layer positions of layer vertex v at time t, interpolated linearly between the layers around t (the
// prism frame's rule, written out here).
Eigen::MatrixXd frame_at(const MatrixX4dRow& V, const AnimationManifold& m, int n, double t) {
  int i = 0;
  while (i + 2 < m.num_layers() && m.times[i + 1] <= t) ++i;
  const double u = (t - m.times[i]) / (m.times[i + 1] - m.times[i]);
  return (1 - u) * V.block(i * n, 0, n, 3) + u * V.block((i + 1) * n, 0, n, 3);
}

struct ArmScene {
  TriMesh arm;
  AnimationManifold M;
  Eigen::Vector3d wrist_mid;  // the wrist at the middle key
};

ArmScene arm_scene(const std::string& path, int inbetweens) {
  ArmScene s;
  s.arm = read_surface(path);
  const std::vector<Eigen::MatrixXd> keys = {bent_arm(s.arm.V, 0), bent_arm(s.arm.V, 50), bent_arm(s.arm.V, 10)};
  s.M = keyed_manifold(keys, s.arm.F, inbetweens);
  const Eigen::Vector3d wrist(0.5987815, -0.077609889, 0.065252126), elbow(0.081400687, 0.18519857, -0.042544638);
  s.wrist_mid = Eigen::AngleAxisd(50 * M_PI / 180, Eigen::Vector3d::UnitZ()) * (wrist - elbow) + elbow;
  return s;
}

}  // namespace

TEST_CASE("manifold Laplacian: reciprocal edge-length weights, Eq. 4.1 by hand", "[manifold_edit]") {
  // One tetrahedron slab is enough: vertex 0's ring is the other three.
  TriMesh tri;
  AnimationManifold m;
  m.V.resize(4, 4);
  m.V << 0, 0, 0, 0, 1, 0, 0, 0, 0, 2, 0, 0, 0, 0, 0, 1;
  m.T.resize(1, 4);
  m.T << 0, 1, 2, 3;
  const auto L = manifold_laplacian_rows(m, {0});
  REQUIRE(L[0].neighbours == std::vector<int>{1, 2, 3});
  const double s = 1 + 0.5 + 1;  // 1/|e| for lengths 1, 2, 1
  CHECK(L[0].weights[0] == Approx(1 / s));
  CHECK(L[0].weights[1] == Approx(0.5 / s));
  CHECK(L[0].weights[2] == Approx(1 / s));
  const Eigen::MatrixXd D = differential_coordinates(m, {0}, L);
  CHECK(D(0, 0) == Approx(-1 / s));
  CHECK(D(0, 1) == Approx(-1 / s));
  CHECK(D(0, 3) == Approx(-1 / s));
}

TEST_CASE("space-time edit of the keyed arm: exactness, window, smooth in time, volume", "[manifold_edit]") {
  DFM_DATA_OR_SKIP(path, "arm.obj");
  const ArmScene S = arm_scene(path, 8);
  const AnimationManifold& M = S.M;
  const int n = S.arm.num_vertices();
  // 4.3: edit at the middle key's time (t = 1) over half the animation.
  EditRegionSpec rs;
  rs.center = S.wrist_mid;
  rs.radius = 0.35;
  rs.t0 = 0.5;
  rs.t1 = 1.5;
  EditHandleSpec hs;
  hs.point = S.wrist_mid;
  hs.time = 1.0;
  const EditRegion sel = select_edit_region(M, rs, hs);
  // One factorisation for every check below (each drag is a back substitution; 4.6.1).
  const ManifoldEditor ed(M, sel, hs.point);
  INFO("region " << sel.region.size() << " anchors " << sel.anchors.size() << " handle " << sel.handle.size());
  REQUIRE(sel.handle.size() > 10);
  // The handle is on the key layer at t = 1 only (layer 9), within radius / 4.
  for (int v : sel.handle) {
    REQUIRE(M.V(v, 3) == 1.0);
    REQUIRE((M.V.row(v).head<3>().transpose() - hs.point).norm() <= rs.radius / 4);
  }
  const Eigen::Vector3d move(0.05, 0.12, -0.04);

  {  // a move of zero changes nothing, bit for bit
    const MatrixX4dRow V = ed.drag(ManifoldDrag{});
    REQUIRE((V.array() == M.V.array()).all());
  }

  {  // the handle lands exactly where dragged; slices outside [t0, t1] unchanged; t kept
    ManifoldDrag d;
    d.translation = move;
    const MatrixX4dRow V = ed.drag(d);
    for (int v : sel.handle)
      for (int c = 0; c < 3; ++c) REQUIRE(V(v, c) == M.V(v, c) + move[c]);
    REQUIRE((V.col(3).array() == M.V.col(3).array()).all());
    for (int v : sel.anchors) REQUIRE((V.row(v).array() == M.V.row(v).array()).all());
    AnimationManifold E = M;
    E.V = V;
    for (double t : {0.0, 0.2, 0.49, 0.5 - 1e-9, 1.5 + 1e-9, 1.51, 1.8, 2.0}) {
      const ManifoldSlice a = slice_manifold(M, SliceAxis::T, t), b = slice_manifold(E, SliceAxis::T, t);
      INFO("t = " << t);
      REQUIRE(a.mesh.V.rows() == b.mesh.V.rows());
      REQUIRE((a.mesh.V.array() == b.mesh.V.array()).all());
      REQUIRE((a.mesh.F.array() == b.mesh.F.array()).all());
    }
    // And something did move inside the window.
    REQUIRE((V - M.V).rowwise().norm().maxCoeff() > 0.1);
  }

  {  // translating every region vertex with the handle gives exactly that translation
    EditRegion all = sel;
    all.handle = all.region;
    const ManifoldEditor whole(M, all, hs.point);
    ManifoldDrag d;
    d.translation = move;
    const MatrixX4dRow V = whole.drag(d);
    std::vector<char> in(M.num_vertices(), 0);
    for (int v : all.region) in[v] = 1;
    int wrong = 0;  // one assertion for the whole matrix: Catch per entry costs seconds
    for (int v = 0; v < M.num_vertices(); ++v)
      for (int c = 0; c < 4; ++c) wrong += V(v, c) != (in[v] && c < 3 ? M.V(v, c) + move[c] : M.V(v, c));
    REQUIRE(wrong == 0);
  }

  {  // smooth in time: the handle point's displacement over 41 times against a smoothstep
    ManifoldDrag d;
    d.translation = move;
    const MatrixX4dRow V = ed.drag(d);
    // The handle vertex nearest the handle point, followed through time as a layer vertex.
    int h = sel.handle.front();
    for (int v : sel.handle)
      if ((M.V.row(v).head<3>().transpose() - hs.point).norm() < (M.V.row(h).head<3>().transpose() - hs.point).norm()) h = v;
    const int lv = h % n;
    std::vector<double> curve, ref;
    for (int k = 0; k <= 40; ++k) {
      const double t = rs.t0 + (rs.t1 - rs.t0) * k / 40.0;
      const Eigen::RowVector3d disp = frame_at(V, M, n, t).row(lv) - frame_at(M.V, M, n, t).row(lv);
      curve.push_back(disp.dot(move.transpose()) / move.squaredNorm());
      ref.push_back(t <= hs.time ? smoothstep((t - rs.t0) / (hs.time - rs.t0)) : smoothstep((rs.t1 - t) / (rs.t1 - hs.time)));
    }
    auto max_second = [](const std::vector<double>& c) {
      double m = 0;
      for (size_t i = 1; i + 1 < c.size(); ++i) m = std::max(m, std::abs(c[i - 1] - 2 * c[i] + c[i + 1]));
      return m;
    };
    std::string text;
    for (double c : curve) text += std::to_string(c).substr(0, 6) + " ";
    std::printf("smooth in time: displacement / move at 41 times over [%g, %g]: %s\n", rs.t0, rs.t1, text.c_str());
    std::printf("smooth in time: max second difference %.4g, smoothstep's %.4g (ratio %.2f)\n", max_second(curve),
                max_second(ref), max_second(curve) / max_second(ref));
    REQUIRE(curve.front() == 0.0);
    REQUIRE(curve.back() == 0.0);
    REQUIRE(curve[20] == Approx(1.0).margin(1e-12));
    for (size_t k = 0; k + 1 < curve.size(); ++k) {
      INFO("k = " << k);
      if (k < 20) REQUIRE(curve[k + 1] >= curve[k] - 1e-9);  // rises
      else REQUIRE(curve[k + 1] <= curve[k] + 1e-9);         // falls
    }
    REQUIRE(max_second(curve) <= 10 * max_second(ref));
  }

  {  // --volume: every frame's enclosed volume in the window within 1% of the original
    ManifoldEditOptions opt;
    opt.preserve_volume = true;
    const ManifoldEditor& plain_editor = ed;
    const ManifoldEditor edv(M, sel, hs.point, opt);
    ManifoldDrag d;
    d.translation = Eigen::Vector3d(0.0, 0.2, 0.0);
    const MatrixX4dRow V = edv.drag(d), P = plain_editor.drag(d);
    double worst = 0, worst_plain = 0;
    for (int k = 0; k <= 40; ++k) {
      const double t = rs.t0 + (rs.t1 - rs.t0) * k / 40.0;
      const double v0 = mesh_volume(frame_at(M.V, M, n, t), S.arm.F);
      worst = std::max(worst, std::abs(mesh_volume(frame_at(V, M, n, t), S.arm.F) / v0 - 1));
      worst_plain = std::max(worst_plain, std::abs(mesh_volume(frame_at(P, M, n, t), S.arm.F) / v0 - 1));
    }
    std::printf("volume: largest relative change over 41 frames: %.3g%% with --volume, %.3g%% without\n", 100 * worst,
                100 * worst_plain);
    REQUIRE(worst < 0.01);
    for (int v : sel.handle)
      for (int c = 0; c < 3; ++c) REQUIRE(V(v, c) == M.V(v, c) + d.translation[c]);
  }

  {  // --time-scale: a turned wrist handle carries the fingers when the time edges weigh less
    ManifoldDrag d;
    d.rotation = Eigen::AngleAxisd(-M_PI / 4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    d.translation = Eigen::Vector3d(0.05, -0.3, 0);
    // The mean turn (about z, in degrees) of the layer at t = 1's vertices past the wrist, 0.2-0.3 from the
    // handle point, measured from the moved handle point.
    auto finger_turn = [&](const MatrixX4dRow& V) {
      double sum = 0;
      int count = 0;
      for (int v = 9 * n; v < 10 * n; ++v) {
        const Eigen::Vector3d p = M.V.row(v).head<3>().transpose(), q = V.row(v).head<3>().transpose();
        const double dist = (p - hs.point).norm();
        if (p.x() < hs.point.x() || dist < 0.2 || dist >= 0.3) continue;
        const Eigen::Vector3d a = p - hs.point, b = q - hs.point - d.translation;
        sum += std::remainder(std::atan2(b.y(), b.x()) - std::atan2(a.y(), a.x()), 2 * M_PI);
        ++count;
      }
      REQUIRE(count > 100);
      return sum / count * 180 / M_PI;
    };
    // A wider region than above, so the fingers are well inside it (its anchors 0.45 from the wrist).
    EditRegionSpec wide = rs;
    wide.radius = 0.45;
    const EditRegion wsel = select_edit_region(M, wide, hs);
    ManifoldEditOptions opt;
    opt.time_scale = 10;
    const ManifoldEditor scaled(M, wsel, hs.point, opt);
    const MatrixX4dRow V = scaled.drag(d);
    const double t10 = finger_turn(V);
    // (With time scale 1 the same fingers lag behind the moved wrist: +31 to +35 degrees; README.)
    std::printf("time scale: fingers 0.2-0.3 past a wrist handle turned by -45 degrees turn %.1f degrees with time "
                "scale 10\n", t10);
    CHECK(std::abs(t10 + 45) < 10);
    for (int v : wsel.handle) {
      const Eigen::Vector3d p = M.V.row(v).head<3>().transpose();
      REQUIRE((V.row(v).head<3>().transpose() - (d.rotation * (p - hs.point) + hs.point + d.translation)).norm() == 0.0);
    }
    CHECK_THROWS_WITH(manifold_laplacian_rows(M, sel.region, LaplacianWeights::Reciprocal, 0.0), Catch::Contains("time scale"));
  }

  {  // hostile input: a clear error, nothing selected
    EditRegionSpec far = rs;
    far.center = Eigen::Vector3d(10, 10, 10);
    CHECK_THROWS_WITH(select_edit_region(M, far, hs), Catch::Contains("no manifold vertex"));
    EditRegionSpec late = rs;
    late.t0 = 3;
    late.t1 = 4;
    EditHandleSpec late_h = hs;
    late_h.time = 3.5;
    CHECK_THROWS_WITH(select_edit_region(M, late, late_h), Catch::Contains("outside the animation"));
    EditHandleSpec off = hs;
    off.point = S.wrist_mid + Eigen::Vector3d(0.5, 0, 0);  // outside the region's ball
    CHECK_THROWS_WITH(select_edit_region(M, rs, off), Catch::Contains("no region vertex"));
    EditHandleSpec before = hs;
    before.time = 0.2;
    CHECK_THROWS_WITH(select_edit_region(M, rs, before), Catch::Contains("outside the window"));
    EditRegionSpec bad = rs;
    bad.radius = -1;
    CHECK_THROWS_WITH(select_edit_region(M, bad, hs), Catch::Contains("radius"));
    ManifoldDrag nan_drag;
    nan_drag.translation.x() = NAN;
    CHECK_THROWS_WITH(ed.drag(nan_drag), Catch::Contains("not finite"));
    ManifoldDrag shear;
    shear.rotation(0, 1) = 0.5;
    CHECK_THROWS_WITH(ed.drag(shear), Catch::Contains("not a rotation"));
  }
}

TEST_CASE("details turn with the drag (4.2.1): a bump follows a 90 degree handle turn", "[manifold_edit]") {
  // A sheet over [0, 2] x [0, 1] with a Gaussian bump at (1.5, 0.5), standing still over 9 layers.
  const int nx = 61, ny = 31;
  TriMesh sheet;
  sheet.V.resize(nx * ny, 3);
  const Eigen::Vector2d bump(1.5, 0.5);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Eigen::Vector2d p(2.0 * i / (nx - 1), 1.0 * j / (ny - 1));
      sheet.V.row(j * nx + i) << p.x(), p.y(), 0.08 * std::exp(-(p - bump).squaredNorm() / (2 * 0.05 * 0.05));
    }
  sheet.F.resize(2 * (nx - 1) * (ny - 1), 3);
  for (int j = 0, f = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const int a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
      sheet.F.row(f++) << a, b, d;
      sheet.F.row(f++) << a, d, c;
    }
  const int n = sheet.num_vertices();
  const AnimationManifold M = build_manifold(std::vector<Eigen::MatrixXd>(9, sheet.V), sheet.F,
                                             {0, 1, 2, 3, 4, 5, 6, 7, 8});
  EditRegionSpec rs;
  rs.center = Eigen::Vector3d(1.2, 0.5, 0);
  rs.radius = 0.8;
  rs.t0 = 0;
  rs.t1 = 8;
  EditHandleSpec hs;
  hs.point = Eigen::Vector3d(1.85, 0.5, 0);
  hs.time = 4;
  const EditRegion sel = select_edit_region(M, rs, hs);
  // The bump's vertices are free: outside the handle's ball.
  const int apex = 4 * n + (ny / 2) * nx + 45;
  REQUIRE(M.V.row(apex).head<2>().transpose().isApprox(bump));
  REQUIRE(!std::binary_search(sel.handle.begin(), sel.handle.end(), apex));
  REQUIRE(std::binary_search(sel.region.begin(), sel.region.end(), apex));
  // The bump's normal: apex minus the mean of the square ring 3 grid steps (2 sigma) around it.
  auto bump_normal = [&](const MatrixX4dRow& V) {
    Eigen::Vector3d ring = Eigen::Vector3d::Zero();
    int count = 0;
    for (int dj = -3; dj <= 3; ++dj)
      for (int di = -3; di <= 3; ++di)
        if (std::max(std::abs(di), std::abs(dj)) == 3) {
          ring += V.row(apex + dj * nx + di).head<3>().transpose();
          ++count;
        }
    return Eigen::Vector3d(V.row(apex).head<3>().transpose() - ring / count).normalized();
  };
  REQUIRE(bump_normal(M.V).isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
  ManifoldDrag d;
  d.rotation = Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();  // the end turns up
  d.translation = Eigen::Vector3d(0, 0, 0);
  const Eigen::Vector3d want = d.rotation * Eigen::Vector3d::UnitZ();
  auto angle = [&](const Eigen::Vector3d& a) { return std::acos(std::clamp(a.dot(want), -1.0, 1.0)) * 180 / M_PI; };

  const ManifoldEditor ed(M, sel, hs.point);
  const double turned = angle(bump_normal(ed.drag(d)));
  ManifoldEditOptions plain;
  plain.turn_details = false;  // translation-only Laplacian editing (4.2's first shortcoming)
  const double sheared = angle(bump_normal(ManifoldEditor(M, sel, hs.point, plain).drag(d)));
  std::printf("details turn: bump normal %.2f degrees from the turned normal (%.2f with unturned details; reach at "
              "the apex %.3f)\n", turned, sheared,
              ed.reach()[std::lower_bound(sel.region.begin(), sel.region.end(), apex) - sel.region.begin()]);
  REQUIRE(sheared > 30);
  REQUIRE(turned < 10);
  // Handle vertices are placed rigidly.
  const MatrixX4dRow V = ed.drag(d);
  for (int v : sel.handle) {
    const Eigen::Vector3d p = M.V.row(v).head<3>().transpose();
    REQUIRE((V.row(v).head<3>().transpose() - (d.rotation * (p - hs.point) + hs.point)).norm() == 0.0);
  }
}

TEST_CASE("primal boundary weights (4.4.1, Eq. 4.3): the simplex projection's KKT conditions and a closed form",
          "[manifold_edit]") {
  // Projection onto {sum w = 1, w >= xi}: w_i > xi share one y_i - w_i = tau, w_i = xi have y_i - xi <= tau.
  Eigen::VectorXd y(6);
  y << 0.9, -0.3, 0.4, 0.05, 1.7, -2.0;
  const double xi = 0.01;
  const Eigen::VectorXd w = project_shifted_simplex(y, xi);
  REQUIRE(w.sum() == Approx(1).margin(1e-14));
  double tau = NAN;
  for (int i = 0; i < 6; ++i) {
    REQUIRE(w[i] >= xi - 1e-15);
    if (w[i] > xi + 1e-12) {
      if (std::isnan(tau)) tau = y[i] - w[i];
      REQUIRE(y[i] - w[i] == Approx(tau).margin(1e-12));
    }
  }
  for (int i = 0; i < 6; ++i)
    if (w[i] <= xi + 1e-12) REQUIRE(y[i] - xi <= tau + 1e-12);

  // A boundary vertex at the origin with neighbours +-x, +y and +t (its ring one-sided in y and t):
  // delta = -(w1 - w2, w3, 0, w4), so the minimum puts w3 = w4 = xi and w1 = w2 = (1 - 2 xi) / 2,
  // |delta|^2 = 2 xi^2; the reciprocal (here equal) weights leave |delta|^2 = 1 / 8.
  Eigen::MatrixXd N(4, 4);
  N << 1, 0, 0, 0, -1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 1;
  PrimalWeightOptions o;
  o.xi = 0.02;
  const Eigen::VectorXd w0 = Eigen::VectorXd::Constant(4, 0.25);
  const Eigen::VectorXd pw = primal_boundary_weights(Eigen::Vector4d::Zero(), N, w0, o);
  INFO("weights " << pw.transpose());
  CHECK(pw[0] == Approx(0.48).margin(1e-3));
  CHECK(pw[1] == Approx(0.48).margin(1e-3));
  CHECK(pw[2] == Approx(0.02).margin(1e-6));
  CHECK(pw[3] == Approx(0.02).margin(1e-6));
  CHECK((N.transpose() * pw).squaredNorm() == Approx(2 * 0.02 * 0.02).epsilon(0.05));
  CHECK_THROWS_AS(primal_boundary_weights(Eigen::Vector4d::Zero(), N, w0, PrimalWeightOptions{0.3}), Error);
}

TEST_CASE("weighting schemes (4.6.1) on the arm's first layer: boundary rows, smaller deltas, exact handle",
          "[manifold_edit]") {
  DFM_DATA_OR_SKIP(path, "arm.obj");
  const ArmScene S = arm_scene(path, 2);
  const AnimationManifold& M = S.M;
  // A window from the start of the animation: the first layer (t = 0) is the manifold's open boundary.
  EditRegionSpec rs;
  rs.center = S.arm.V.row(0).transpose();
  rs.radius = 0.2;
  rs.t0 = 0;
  rs.t1 = 1;
  EditHandleSpec hs;
  hs.point = rs.center;
  hs.time = 0;
  const EditRegion sel = select_edit_region(M, rs, hs);
  const std::vector<char> boundary = manifold_boundary_rows(M, sel.region);
  int nb = 0;
  for (size_t r = 0; r < sel.region.size(); ++r) {
    nb += boundary[r];
    REQUIRE(bool(boundary[r]) == (M.V(sel.region[r], 3) == 0.0));  // the prism manifold's boundary: t = 0
  }
  REQUIRE(nb > 0);
  const auto rec = manifold_laplacian_rows(M, sel.region, LaplacianWeights::Reciprocal);
  const auto pri = manifold_laplacian_rows(M, sel.region, LaplacianWeights::PrimalBoundary);
  const auto eq = manifold_laplacian_rows(M, sel.region, LaplacianWeights::Equal);
  const Eigen::MatrixXd dr = differential_coordinates(M, sel.region, rec), dp = differential_coordinates(M, sel.region, pri),
                        de = differential_coordinates(M, sel.region, eq);
  double sr = 0, sp = 0, se = 0;
  for (size_t r = 0; r < sel.region.size(); ++r) {
    REQUIRE(eq[r].weights.front() == 1.0 / eq[r].neighbours.size());
    if (!boundary[r]) {
      REQUIRE(pri[r].weights == rec[r].weights);
      continue;
    }
    double sum = 0;
    for (double x : pri[r].weights) {
      sum += x;
      REQUIRE(x > 0);
    }
    REQUIRE(sum == Approx(1).margin(1e-12));
    sr += dr.row(r).norm(), sp += dp.row(r).norm(), se += de.row(r).norm();
  }
  std::printf("boundary rows %d: mean |delta| equal %.4g, reciprocal %.4g, primal boundary (Eq. 4.3) %.4g\n", nb, se / nb,
              sr / nb, sp / nb);
  REQUIRE(sp < 0.5 * sr);
  for (LaplacianWeights w : {LaplacianWeights::Equal, LaplacianWeights::PrimalBoundary}) {
    ManifoldEditOptions opt;
    opt.weights = w;
    const ManifoldEditor ed(M, sel, hs.point, opt);
    REQUIRE((ed.drag(ManifoldDrag{}).array() == M.V.array()).all());
    ManifoldDrag d;
    d.translation = Eigen::Vector3d(0, 0.05, 0);
    const MatrixX4dRow V = ed.drag(d);
    for (int v : sel.handle)
      for (int c = 0; c < 3; ++c) REQUIRE(V(v, c) == M.V(v, c) + d.translation[c]);
  }
}
