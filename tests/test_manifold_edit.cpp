// Space-time Laplacian editing of animation manifolds (Southern 2008, 4.2-4.4; issue 35):
// core/anim/manifold_edit_region.h, manifold_laplacian.h, manifold_edit.h, manifold_edit_volume.h.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>

#include <catch2/catch.hpp>
#include <Eigen/Geometry>
#include <Eigen/QR>

#include "core/anim/dual_laplacian.h"
#include "core/anim/manifold.h"
#include "core/anim/manifold_edit.h"
#include "core/anim/manifold_edit_region.h"
#include "core/anim/manifold_edit_volume.h"
#include "core/anim/manifold_laplacian.h"
#include "core/anim/manifold_retime.h"
#include "core/mesh/mesh_info.h"
#include "core/anim/primal_boundary_weights.h"
#include "core/anim/slice.h"
#include "core/mesh/io.h"
#include "core/util/error.h"
#include "tests/ellipsoid_test_mesh.h"
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
  // The dual graph Laplacian (Au et al. 2006, with 4.4.2's ghosts at the sheet's first and last layers).
  ManifoldEditOptions dual;
  dual.weights = LaplacianWeights::Dual;
  const ManifoldEditor ed_dual(M, sel, hs.point, dual);
  const MatrixX4dRow Vd = ed_dual.drag(d);
  const double turned_dual = angle(bump_normal(Vd));
  std::printf("details turn, dual Laplacian: bump normal %.2f degrees from the turned normal (primal %.2f); apex "
              "moved %.4f (primal %.4f)\n", turned_dual, turned, (Vd.row(apex) - M.V.row(apex)).norm(),
              (ed.drag(d).row(apex) - M.V.row(apex)).norm());
  REQUIRE(turned_dual < 10);
  REQUIRE((ed_dual.drag(ManifoldDrag{}).array() == M.V.array()).all());
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

TEST_CASE("dual Laplacian (Au et al. 2006) and its ghost boundary condition (4.4.2)", "[manifold_edit]") {
  // The ghost of tetrahedron (A, B, C, D) across its boundary face BCD: A reflected through the face's
  // centroid, the tetrahedron (B, C, D, 2 c_f - A); its centroid by hand.
  Eigen::Matrix<double, 3, 4> face;
  face << 1, 0, 0, 0.5, 0, 2, 0, 0.5, 0, 0, 3, 0.5;
  const Eigen::RowVector4d A(0.2, 0.3, 0.4, 0.0);
  const Eigen::RowVector4d cf = face.colwise().mean();
  const Eigen::RowVector4d ghost_by_hand = (face.row(0) + face.row(1) + face.row(2) + (2 * cf - A)) / 4;
  REQUIRE((ghost_dual_vertex(face, A) - ghost_by_hand).norm() < 1e-15);
  const Eigen::RowVector4d shift(5, -1, 2, 7);  // an affine combination: moves with a translation
  REQUIRE((ghost_dual_vertex(face.rowwise() + shift, A + shift) - (ghost_by_hand + shift)).norm() < 1e-14);

  // Projection weights: the hyperplane t = 0 through the origin and the x, y, z unit points; c = (0.1,
  // 0.2, 0.3, 0.7) projects to (0.1, 0.2, 0.3, 0) = 0.4 o + 0.1 x + 0.2 y + 0.3 z, the rest is normal.
  Eigen::MatrixXd P(4, 4);
  P << 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0;
  const Eigen::VectorXd w = affine_projection_weights(Eigen::RowVector4d(0.1, 0.2, 0.3, 0.7), P);
  REQUIRE((w - Eigen::Vector4d(0.4, 0.1, 0.2, 0.3)).norm() < 1e-14);
  // Degenerate (a repeated point): still the nearest point, weights summing to 1.
  P.row(3) = P.row(2);
  const Eigen::VectorXd wd = affine_projection_weights(Eigen::RowVector4d(0.1, 0.2, 0.3, 0.7), P);
  REQUIRE(wd.sum() == Approx(1).margin(1e-14));
  REQUIRE((P.transpose() * wd - Eigen::Vector4d(0.1, 0.2, 0.0, 0.0)).norm() < 1e-14);

  // A flat manifold (a still square of the z = 0 plane over 4 layers lies in the hyperplane z = 0 of
  // R^4): every dual facet spans that hyperplane, so delta' = 0 on every row -- with the ghosts at the
  // first and last layers. Without them (the boundary face's neighbour dropped), a boundary row's three
  // neighbours span a plane the centroid is off: a tangential delta', which 4.4.2 exists to remove.
  const int nx = 6;
  TriMesh sq;
  sq.V.resize(nx * nx, 3);
  for (int j = 0; j < nx; ++j)
    for (int i = 0; i < nx; ++i) sq.V.row(j * nx + i) << i * 0.2 + 0.01 * j * j, j * 0.2, 0;
  sq.F.resize(2 * (nx - 1) * (nx - 1), 3);
  for (int j = 0, f = 0; j + 1 < nx; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const int a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
      sq.F.row(f++) << a, b, d;
      sq.F.row(f++) << a, d, c;
    }
  const AnimationManifold flat = build_manifold(std::vector<Eigen::MatrixXd>(4, sq.V), sq.F, {0, 0.5, 1, 1.5});
  std::vector<int> all(flat.num_tets());
  for (int k = 0; k < flat.num_tets(); ++k) all[k] = k;
  const std::vector<DualLaplacianRow> rows = dual_laplacian_rows(flat, all);
  int ghost_rows = 0;
  double largest = 0;
  for (const DualLaplacianRow& r : rows) {
    Eigen::RowVector4d d = Eigen::RowVector4d::Zero();
    double sum = 0;
    for (size_t k = 0; k < r.vertices.size(); ++k) d += r.coeffs[k] * flat.V.row(r.vertices[k]), sum += r.coeffs[k];
    REQUIRE(std::abs(sum) < 1e-12);
    largest = std::max(largest, d.norm());
    ghost_rows += r.ghosts > 0;
  }
  REQUIRE(ghost_rows > 0);
  REQUIRE(largest < 1e-12);
  // The same boundary tetrahedron without its ghost: its face neighbours only.
  int probe = -1;
  for (const DualLaplacianRow& r : rows)
    if (r.ghosts == 1 && flat.V(flat.T(r.tet, 0), 3) == 0) probe = r.tet;
  REQUIRE(probe >= 0);
  Eigen::MatrixXd Q(0, 4);
  Eigen::RowVector4d c = Eigen::RowVector4d::Zero();
  for (int j = 0; j < 4; ++j) c += 0.25 * flat.V.row(flat.T(probe, j));
  for (int k = 0; k < flat.num_tets(); ++k) {
    int shared = 0;
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) shared += flat.T(k, a) == flat.T(probe, b);
    if (k == probe || shared != 3) continue;
    Q.conservativeResize(Q.rows() + 1, 4);
    Q.row(Q.rows() - 1).setZero();
    for (int j = 0; j < 4; ++j) Q.row(Q.rows() - 1) += 0.25 * flat.V.row(flat.T(k, j));
  }
  REQUIRE(Q.rows() == 3);
  const Eigen::RowVector4d no_ghost = c - (Q.transpose() * affine_projection_weights(c, Q)).transpose();
  std::printf("dual rows on a flat manifold: largest |delta'| %.2e with ghosts (%d boundary rows); a boundary row "
              "without its ghost %.3g (z part %.1e: tangential)\n", largest, ghost_rows, no_ghost.norm(), no_ghost[2]);
  REQUIRE(no_ghost.norm() > 1e-3);
  REQUIRE(std::abs(no_ghost[2]) < 1e-15);
  REQUIRE_THROWS_WITH(manifold_laplacian_rows(flat, {0}, LaplacianWeights::Dual), Catch::Contains("per tetrahedron"));
  REQUIRE(parse_laplacian_weights("dual") == LaplacianWeights::Dual);
  REQUIRE(std::string(laplacian_weights_name(LaplacianWeights::Dual)) == "dual");
}

TEST_CASE("dual Laplacian editing of the keyed arm: exact handle, window, primal vs dual", "[manifold_edit]") {
  DFM_DATA_OR_SKIP(path, "arm.obj");
  const ArmScene S = arm_scene(path, 2);
  const AnimationManifold& M = S.M;
  EditRegionSpec rs;
  rs.center = S.wrist_mid;
  rs.radius = 0.45;
  rs.t0 = 0;  // from the start: the first layer's boundary rows get ghosts
  rs.t1 = 1.6;
  EditHandleSpec hs;
  hs.point = S.wrist_mid;
  hs.time = 1;
  const EditRegion sel = select_edit_region(M, rs, hs);
  ManifoldDrag d;
  d.translation = Eigen::Vector3d(0, 0.1, 0.05);
  std::vector<MatrixX4dRow> out;
  for (LaplacianWeights w : {LaplacianWeights::Reciprocal, LaplacianWeights::PrimalBoundary, LaplacianWeights::Dual}) {
    ManifoldEditOptions opt;
    opt.weights = w;
    const ManifoldEditor ed(M, sel, hs.point, opt);
    REQUIRE((ed.drag(ManifoldDrag{}).array() == M.V.array()).all());
    const MatrixX4dRow V = ed.drag(d);
    for (int v : sel.handle)
      for (int c = 0; c < 3; ++c) REQUIRE(V(v, c) == M.V(v, c) + d.translation[c]);
    REQUIRE(V.col(3) == M.V.col(3));
    for (int v = 0; v < M.num_vertices(); ++v)
      if (M.V(v, 3) > rs.t1) REQUIRE(V.row(v) == M.V.row(v));
    // The reach along the handle's time line at the first layer (t = 0, on the boundary): how far the
    // drag carries to the animation's start.
    double first = 0;
    int count = 0;
    for (int v : sel.region)
      if (M.V(v, 3) == 0 && (M.V.row(v).head<3>().transpose() - S.wrist_mid).norm() < 0.45) {
        first += (V.row(v) - M.V.row(v)).norm();
        ++count;
      }
    std::printf("keyed arm, %s: mean move at t = 0 of the region's first-layer vertices %.4f (%d), handle move %.4f\n",
                laplacian_weights_name(w), first / std::max(count, 1), count, d.translation.norm());
    out.push_back(V);
  }
  REQUIRE((out[2] - out[0]).norm() > 0);
}

TEST_CASE("retime: the handle moves in t, the slices stay closed, folds are refused", "[manifold_edit]") {
  DFM_DATA_OR_SKIP(path, "arm.obj");
  const ArmScene S = arm_scene(path, 2);  // layers every 1/3
  const AnimationManifold& M = S.M;
  EditRegionSpec rs;
  rs.center = S.wrist_mid;
  rs.radius = 0.45;
  rs.t0 = 0.3;
  rs.t1 = 1.7;
  EditHandleSpec hs;
  hs.point = S.wrist_mid;
  hs.time = 1;
  const EditRegion sel = select_edit_region(M, rs, hs);
  const ManifoldEditor ed(M, sel, hs.point);
  ManifoldDrag d;
  d.translation = Eigen::Vector3d(0, 0.05, 0);
  // Default: t bit for bit.
  REQUIRE(ed.drag(d).col(3) == M.V.col(3));
  d.retime = 0.2;
  AnimationManifold R = M;
  R.V = ed.drag(d);
  for (int v : sel.handle) REQUIRE(R.V(v, 3) == M.V(v, 3) + 0.2);
  for (int v : sel.anchors) REQUIRE(R.V(v, 3) == M.V(v, 3));
  merge_retimed_slabs(R);
  std::printf("retime 0.2: %d layers left of %d (slabs around the edit merged)\n", R.num_layers(), M.num_layers());
  REQUIRE(R.num_layers() < M.num_layers());
  for (double t : {0.1, 0.45, 0.8, 1.0, 1.1, 1.25, 1.5, 1.9}) {
    const ManifoldSlice sl = slice_manifold(R, SliceAxis::T, t);
    INFO("t = " << t);
    // Closed, and of the arm's Euler characteristic: no second sheet where a fold would cut twice.
    REQUIRE(is_closed(sl.mesh.F));
    auto euler = [](const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) { return V.rows() - F.rows() / 2; };
    REQUIRE(euler(sl.mesh.V, sl.mesh.F) == euler(S.arm.V, S.arm.F));
    if (t < rs.t0 || t > rs.t1) {
      const ManifoldSlice before = slice_manifold(M, SliceAxis::T, t);
      REQUIRE(sl.mesh.V == before.mesh.V);
    }
  }
  // The handle's frame: at t = 1 + 0.2 the dragged handle vertices lie exactly on the slice.
  const ManifoldSlice at = slice_manifold(R, SliceAxis::T, 1.0 + 0.2);
  int on = 0;
  for (const auto& e : at.edges) on += e[0] == e[1] && std::binary_search(sel.handle.begin(), sel.handle.end(), e[0]);
  REQUIRE(on > 0);
  // A retime past the anchors' layer (5/3) folds a slab back in time: refused, saying so.
  d.retime = 2.0;
  REQUIRE_THROWS_WITH(ed.drag(d), Catch::Contains("folds the manifold in time"));
  // The first layer bounds the animation: a region holding it cannot be retimed.
  rs.t0 = 0;
  const ManifoldEditor first(M, select_edit_region(M, rs, hs), hs.point);
  d.retime = 0.1;
  REQUIRE_THROWS_WITH(first.drag(d), Catch::Contains("first or last layer"));
  d.retime = NAN;
  REQUIRE_THROWS_WITH(ed.drag(d), Catch::Contains("retime is not finite"));
}

namespace {

// The drag solved from scratch: the region's Laplacian rows (Eq. 4.1) as a dense least-squares problem,
// solved by column-pivoted Householder QR (no normal equations, no Cholesky, no reach shortcut), the
// reach the same way; with `volume` each layer's volume restored as the editor does (4.2.2).
MatrixX4dRow dense_drag(const AnimationManifold& M, const EditRegion& sel, const Eigen::Vector3d& pivot,
                        const ManifoldDrag& d, bool volume) {
  const std::vector<int>& region = sel.region;
  const int nr = static_cast<int>(region.size());
  std::map<int, int> slot;
  for (int r = 0; r < nr; ++r) slot[region[r]] = r;
  const std::vector<LaplacianRow> L = manifold_laplacian_rows(M, region);
  Eigen::MatrixXd A = Eigen::MatrixXd::Identity(nr, nr), delta(nr, 3);
  for (int r = 0; r < nr; ++r) {
    delta.row(r) = M.V.row(region[r]).head<3>();
    for (size_t k = 0; k < L[r].neighbours.size(); ++k) {
      delta.row(r) -= L[r].weights[k] * M.V.row(L[r].neighbours[k]).head<3>();
      if (const auto it = slot.find(L[r].neighbours[k]); it != slot.end()) A(r, it->second) -= L[r].weights[k];
    }
  }
  std::vector<int> free_slots, handle_slots;
  for (int r = 0; r < nr; ++r)
    (std::count(sel.handle.begin(), sel.handle.end(), region[r]) ? handle_slots : free_slots).push_back(r);
  Eigen::MatrixXd AF(nr, free_slots.size()), AH(nr, handle_slots.size());
  for (size_t c = 0; c < free_slots.size(); ++c) AF.col(c) = A.col(free_slots[c]);
  for (size_t c = 0; c < handle_slots.size(); ++c) AH.col(c) = A.col(handle_slots[c]);
  const auto qr = AF.colPivHouseholderQr();
  const Eigen::VectorXd sF = qr.solve(Eigen::VectorXd(-AH * Eigen::VectorXd::Ones(handle_slots.size())));
  Eigen::VectorXd reach = Eigen::VectorXd::Ones(nr);
  for (size_t c = 0; c < free_slots.size(); ++c) reach[free_slots[c]] = sF[c];

  MatrixX4dRow out = M.V;
  Eigen::MatrixXd dH(handle_slots.size(), 3);
  for (size_t c = 0; c < handle_slots.size(); ++c) {
    const Eigen::Vector3d p = M.V.row(region[handle_slots[c]]).head<3>();
    const Eigen::Vector3d target = d.rotation * (p - pivot) + pivot + d.translation;
    out.row(region[handle_slots[c]]).head<3>() = target;
    dH.row(c) = (target - p).transpose();
  }
  const Eigen::AngleAxisd aa(d.rotation);
  Eigen::MatrixXd b(nr, 3);
  for (int r = 0; r < nr; ++r) {
    const Eigen::Matrix3d R = Eigen::AngleAxisd(std::clamp(reach[r], 0.0, 1.0) * aa.angle(), aa.axis()).toRotationMatrix();
    b.row(r) = ((R - Eigen::Matrix3d::Identity()) * delta.row(r).transpose()).transpose();
  }
  const Eigen::MatrixXd dF = qr.solve(Eigen::MatrixXd(b - AH * dH));
  std::vector<int> free_vertex;
  std::vector<double> weight;
  for (size_t c = 0; c < free_slots.size(); ++c) {
    out.row(region[free_slots[c]]).head<3>() += dF.row(c);
    free_vertex.push_back(region[free_slots[c]]);
    const double s = std::clamp(reach[free_slots[c]], 0.0, 1.0);
    weight.push_back(4 * s * (1 - s));
  }
  if (volume) restore_layer_volumes(edit_layers(M, free_vertex, weight), out);
  return out;
}

// An ellipsoid (x half-axis 2) over 7 layers at t = 0..6, its +x end rising with t.
AnimationManifold bending_ellipsoid() {
  const TriMesh e = test::ellipsoid();
  std::vector<Eigen::MatrixXd> layers;
  std::vector<double> times;
  for (int k = 0; k < 7; ++k) {
    Eigen::MatrixXd L = e.V;
    for (int i = 0; i < L.rows(); ++i) L(i, 1) += 0.05 * k * smoothstep(e.V(i, 0) / 2);
    layers.push_back(L);
    times.push_back(k);
  }
  return build_manifold(layers, e.F, times);
}

double max_abs(const MatrixX4dRow& a, const MatrixX4dRow& b) { return (a - b).cwiseAbs().maxCoeff(); }

}  // namespace

// The tolerance: the reach's way, the back substitution and the QR solve differ by rounding only
// (measured: 1.1e-15 at most, a few ulps of the unit-sized coordinates); 1e-12 leaves room for other
// compilers and BLAS and is far below anything a frame shows (the GPU gets floats, 6e-8 apart at 1).
TEST_CASE("a drag without a turn is the reach times the move: equal to a dense solve from scratch; turns and volume "
          "keep the back substitution", "[manifold_edit]") {
  const double tol = 1e-12;
  const AnimationManifold M = bending_ellipsoid();
  EditRegionSpec rs;
  rs.center = {2, 0.15, 0};
  rs.radius = 1.6;
  rs.t0 = 0.5;
  rs.t1 = 5.5;
  EditHandleSpec hs;
  hs.point = {2, 0.15, 0};
  hs.time = 3;
  const EditRegion sel = select_edit_region(M, rs, hs);
  INFO("region " << sel.region.size() << " handle " << sel.handle.size());
  REQUIRE(sel.handle.size() >= 1);
  REQUIRE(sel.region.size() > 50);
  ManifoldEditOptions exact;
  exact.linear_translation = false;
  const ManifoldEditor fast(M, sel, hs.point), solved(M, sel, hs.point, exact);
  std::mt19937 rng(35);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  auto random_move = [&] { return Eigen::Vector3d(u(rng), u(rng), u(rng)); };

  SECTION("translations") {
    for (int i = 0; i < 8; ++i) {
      ManifoldDrag d;
      d.translation = random_move();
      const MatrixX4dRow reference = dense_drag(M, sel, hs.point, d, false), V = fast.drag(d);
      CHECK(max_abs(V, reference) <= tol);
      CHECK(max_abs(solved.drag(d), reference) <= tol);
      CHECK((V - M.V).cwiseAbs().maxCoeff() > 0.1);  // it moved
      // drag_onto over an earlier frame's rows: the region's rows rewritten, nothing else touched.
      MatrixX4dRow W = fast.drag(ManifoldDrag{random_move()});
      fast.drag_onto(d, W);
      CHECK(W == V);
    }
  }
  SECTION("a turn (and a translation): the back substitution, equal to the dense solve") {
    for (int i = 0; i < 4; ++i) {
      ManifoldDrag d;
      d.translation = random_move();
      d.rotation = Eigen::AngleAxisd(u(rng) * 2, random_move().normalized()).toRotationMatrix();
      const MatrixX4dRow V = fast.drag(d);
      CHECK(V == solved.drag(d));
      CHECK(max_abs(V, dense_drag(M, sel, hs.point, d, false)) <= tol);
    }
  }
  SECTION("after a turn edit: translations on the turned manifold") {
    ManifoldDrag turn;
    turn.rotation = Eigen::AngleAxisd(0.6, Eigen::Vector3d(0.2, 0.3, 1).normalized()).toRotationMatrix();
    turn.translation = {0, 0.2, 0};
    AnimationManifold T = M;
    T.V = fast.drag(turn);
    const EditRegion sel2 = select_edit_region(T, rs, hs);
    const ManifoldEditor fast2(T, sel2, hs.point);
    for (int i = 0; i < 4; ++i) {
      ManifoldDrag d;
      d.translation = random_move();
      CHECK(max_abs(fast2.drag(d), dense_drag(T, sel2, hs.point, d, false)) <= tol);
    }
  }
  SECTION("volume preservation: the back substitution, then the volumes") {
    ManifoldEditOptions vol, vol_exact;
    vol.preserve_volume = vol_exact.preserve_volume = true;
    vol_exact.linear_translation = false;
    const ManifoldEditor fv(M, sel, hs.point, vol), sv(M, sel, hs.point, vol_exact);
    for (int i = 0; i < 4; ++i) {
      ManifoldDrag d;
      d.translation = random_move();
      const MatrixX4dRow V = fv.drag(d);
      CHECK(V == sv.drag(d));
      CHECK(max_abs(V, dense_drag(M, sel, hs.point, d, true)) <= tol);
      CHECK(max_abs(V, dense_drag(M, sel, hs.point, d, false)) > 1e-4);  // the volumes did change it
    }
  }
}
