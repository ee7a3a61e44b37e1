#pragma once
// Shared by the glTF tests: a small synthetic rig with every handle kind, smooth synthetic weights,
// and a few keyed poses.
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "core/export/gltf_export.h"
#include "core/rig/forward_kinematics.h"
#include "core/rig/rig.h"

namespace dfm::test {

// Open tube along x from 0 to `length`, radius r.
inline TriMesh tube(int rings, int around, double length, double r) {
  TriMesh m;
  m.V.resize(rings * around, 3);
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < around; ++j) {
      const double a = 2 * M_PI * j / around;
      m.V.row(i * around + j) << length * i / (rings - 1), r * std::cos(a), r * std::sin(a);
    }
  m.F.resize(2 * (rings - 1) * around, 3);
  int f = 0;
  for (int i = 0; i + 1 < rings; ++i)
    for (int j = 0; j < around; ++j) {
      const int a = i * around + j, b = i * around + (j + 1) % around, c = a + around, d = b + around;
      m.F.row(f++) << a, c, b;
      m.F.row(f++) << b, c, d;
    }
  return m;
}

inline double point_segment_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

// Smooth, dense synthetic weights (NOT bbw): inverse distance to each handle, w ~ 1/(d^p + eps),
// normalized per vertex. Bones use the distance to their segment, regions to their centroid.
inline Eigen::MatrixXd inverse_distance_weights(const TriMesh& S, const Rig& rig, double power = 4.0) {
  const int nh = num_handles(rig);
  const double diag = (S.V.colwise().maxCoeff() - S.V.colwise().minCoeff()).norm();
  Eigen::MatrixXd W(S.V.rows(), nh);
  for (int v = 0; v < S.V.rows(); ++v) {
    const Eigen::Vector3d p = S.V.row(v).transpose();
    for (int h = 0; h < nh; ++h) {
      const HandleRef ref = handle_ref(rig, h);
      double d = 0;
      switch (ref.kind) {
        case HandleKind::Point: d = (p - rig.points[ref.index].position).norm(); break;
        case HandleKind::Bone: {
          const Bone& b = rig.skeleton.bones[ref.index];
          d = point_segment_distance(p, rig.skeleton.joints.row(b.a).transpose(), rig.skeleton.joints.row(b.b).transpose());
          break;
        }
        case HandleKind::CageVertex: d = (p - rig.cages[ref.cage].mesh.V.row(ref.index).transpose()).norm(); break;
        case HandleKind::Region: {
          Eigen::Vector3d c = Eigen::Vector3d::Zero();
          for (int i : rig.regions[ref.index].vertices) c += S.V.row(i).transpose();
          c /= std::max<size_t>(1, rig.regions[ref.index].vertices.size());
          d = (p - c).norm();
          break;
        }
      }
      W(v, h) = 1.0 / (std::pow(d / diag, power) + 1e-12);
    }
    W.row(v) /= W.row(v).sum();
  }
  return W;
}

// 2 points, a 3-bone chain, a 4-vertex cage, 1 region: 10 handles.
inline Rig synthetic_rig(const TriMesh& S) {
  Rig rig;
  rig.points.push_back({Eigen::Vector3d(0.5, 0.6, 0.0), "p0"});
  rig.points.push_back({Eigen::Vector3d(2.5, -0.6, 0.1), "p1"});
  rig.skeleton.joints.resize(4, 3);
  rig.skeleton.joints << 0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0;
  rig.skeleton.bones = {{0, 1, -1, "b0"}, {1, 2, -1, "b1"}, {2, 3, -1, "b2"}};
  compute_bone_parents(rig.skeleton);
  Cage cage;
  cage.name = "tip";
  cage.mesh.V.resize(4, 3);
  cage.mesh.V << 3.2, 0.5, 0.5, 3.2, -0.5, 0.5, 3.2, 0.0, -0.6, 3.6, 0.0, 0.0;
  cage.mesh.F.resize(4, 3);
  cage.mesh.F << 0, 1, 2, 0, 3, 1, 1, 3, 2, 2, 3, 0;
  rig.cages.push_back(cage);
  Region region;
  region.name = "base";
  for (int v = 0; v < S.V.rows(); ++v)
    if (S.V(v, 0) < 0.15) region.vertices.push_back(v);
  rig.regions.push_back(region);
  return rig;
}

inline Eigen::Quaterniond axis_angle(double angle, Eigen::Vector3d axis) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized()));
}

// A pose of the synthetic rig scaled by s (s = 0: rest). Bones by forward kinematics (rigid),
// points rotate about themselves and translate, cage vertices translate, the region gets a rotation
// with uniform scale (a TRS-expressible affine) unless `shear` is set.
inline Pose synthetic_pose(const Rig& rig, double s, bool shear = false) {
  Pose pose;
  const Eigen::Vector3d z(0, 0, 1), y(0, 1, 0);
  for (int i = 0; i < static_cast<int>(rig.points.size()); ++i) {
    const Eigen::Vector3d c = rig.points[i].position;
    Eigen::Affine3d T = Eigen::Translation3d(c + s * Eigen::Vector3d(0.1, 0.2 * (i + 1), -0.1)) *
                        axis_angle(0.7 * s * (i + 1), Eigen::Vector3d(1, 1, 0)) * Eigen::Translation3d(-c);
    pose.transforms.push_back(T);
  }
  const std::vector<Eigen::Quaterniond> rot = {axis_angle(0.4 * s, z), axis_angle(-0.9 * s, y),
                                               axis_angle(1.3 * s, Eigen::Vector3d(1, 2, 3))};
  const std::vector<Eigen::Vector3d> tr = {Eigen::Vector3d(0.1, -0.2, 0.3) * s};
  for (const auto& T : forward_kinematics(rig.skeleton, rot, tr)) pose.transforms.push_back(T);
  for (int i = 0; i < rig.cages[0].mesh.V.rows(); ++i)
    pose.transforms.push_back(Eigen::Affine3d(Eigen::Translation3d(s * Eigen::Vector3d(0.05 * i, 0.3, -0.2))));
  Eigen::Affine3d R = Eigen::Affine3d::Identity();
  R.linear() = (1.0 + 0.3 * s) * axis_angle(0.5 * s, Eigen::Vector3d(0, 1, 1)).toRotationMatrix();
  if (shear) R.linear()(0, 1) += 0.4;
  R.translation() = Eigen::Vector3d(0, 0.2, 0) * s;
  pose.transforms.push_back(R);
  return pose;
}

inline GltfExportInput synthetic_input() {
  GltfExportInput in;
  in.name = "tube";
  in.surface = tube(31, 16, 3.0, 0.3);
  in.rig = synthetic_rig(in.surface);
  in.weights = inverse_distance_weights(in.surface, in.rig);
  in.current = synthetic_pose(in.rig, 0.5);
  in.keys = {{0.0, synthetic_pose(in.rig, 0.0)}, {0.5, synthetic_pose(in.rig, 1.0)}, {1.25, synthetic_pose(in.rig, -0.8)}};
  return in;
}

}  // namespace dfm::test
