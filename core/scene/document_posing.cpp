// Document commands that pose and key: handle transforms, FAST posing, keys (document.h).
#include "core/scene/document.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/anim/transition.h"
#include "core/mesh/io.h"
#include "core/rig/forward_kinematics.h"
#include "core/scene/document_parts.h"
#include "core/util/error.h"

namespace dfm {

using document_detail::check_finite;

// ---- posing ----------------------------------------------------------------------------------------

namespace {
void check_params_fit(const Rig& rig, const PoseParams& p) {
  const size_t nb = rig.skeleton.num_bones(), np = num_point_handles(rig), nc = num_cage_vertices(rig);
  if (p.bone_rotation.size() != nb || p.bone_translation.size() != nb || p.point_translation.size() != np ||
      p.point_rotation.size() != np || p.cage_translation.size() != nc ||
      p.region_transform.size() != rig.regions.size() ||
      (!p.bone_twist_stretch.empty() && p.bone_twist_stretch.size() != nb))
    throw Error("pose parameters do not match the rig's handles");
  auto finite_q = [](const Eigen::Quaterniond& q) { return q.coeffs().allFinite() && q.norm() > 1e-12; };
  for (const auto& q : p.bone_rotation)
    if (!finite_q(q)) throw Error("pose: bone rotation is not a valid quaternion");
  for (const auto& q : p.point_rotation)
    if (!finite_q(q)) throw Error("pose: point rotation is not a valid quaternion");
  for (const auto* v : {&p.bone_translation, &p.point_translation, &p.cage_translation})
    for (const auto& x : *v)
      if (!x.allFinite()) throw Error("pose: translation is not finite");
  for (const auto& T : p.region_transform)
    if (!T.matrix().allFinite()) throw Error("pose: region transform is not finite");
}

}  // namespace

void Document::set_pose_params(const PoseParams& p) {
  PoseParams q = p;
  if (q.bone_twist_stretch.empty()) q.bone_twist_stretch.assign(s_.rig.skeleton.num_bones(), BoneTwistStretch{});
  check_params_fit(s_.rig, q);
  execute("pose", kPose, "pose", [&](SceneData& s) { s.pose = std::move(q); });
}

DragReport Document::translate_handle(int handle, const Eigen::Vector3d& d) {
  return move_handle(handle, d, s_.posing.fast);
}

namespace {

// Whether a bone above `bone` (through bone_attachments) is free: a drag on the bone can then run the
// chain as IK.
bool free_bone_above(const Rig& rig, const std::vector<HandleConstraint>& states, int bone) {
  const std::vector<int> to = bone_attachments(rig.skeleton);
  const int np = num_point_handles(rig);
  for (int b = to[bone], steps = 0; b >= 0 && steps <= rig.skeleton.num_bones(); b = to[b], ++steps)
    if (states[np + b] == HandleConstraint::Free) return true;
  return false;
}

}  // namespace

DragReport Document::move_handle(int handle, const Eigen::Vector3d& d, bool solve) {
  check_finite(d, "translation");
  dyn_keep_ = false;
  const HandleRef r = handle_ref(s_.rig, handle);
  const std::string name = handle_name(s_.rig, handle);
  DragReport report{DragKind::Moved, "moved " + name};
  Eigen::Quaterniond turn = Eigen::Quaterniond::Identity();  // for DragKind::Rotated, in world space
  if (r.kind == HandleKind::Bone && bone_attachments(s_.rig.skeleton)[r.index] >= 0) {
    const std::vector<HandleConstraint> states = handle_states();
    if (solve && has_weights() && states[handle] == HandleConstraint::Position &&
        free_bone_above(s_.rig, states, r.index)) {
      report = {DragKind::Ik, "IK: " + name + "'s tip follows the drag, the free bones above it are solved (FAST)"};
    } else {
      // Turn about the first joint, the tip toward tip + d (the shortest arc). The bone's own
      // parameters give its direction: a solved transform is FAST's, not what the drag turns.
      PoseParams base = s_.pose;
      base.solved.clear();
      const Eigen::Affine3d T = evaluate_pose(s_.rig, base).transforms[handle];
      const Bone& b = s_.rig.skeleton.bones[r.index];
      const Eigen::Vector3d a = s_.rig.skeleton.joints.row(b.a).transpose(), e = s_.rig.skeleton.joints.row(b.b).transpose();
      const Eigen::Vector3d from = T.linear() * (e - a), to = from + d;
      if (from.norm() > 0 && to.norm() > 1e-12 * from.norm()) turn = Eigen::Quaterniond::FromTwoVectors(from, to);
      const int to_bone = bone_attachments(s_.rig.skeleton)[r.index];
      const std::string joint = b.parent >= 0 ? "where " + s_.rig.skeleton.bones[to_bone].name + " ends"
                                              : "shared with " + s_.rig.skeleton.bones[to_bone].name;
      const long deg = std::lround(turn.angularDistance(Eigen::Quaterniond::Identity()) * 180.0 / M_PI);
      report = {DragKind::Rotated, name + " turned " + std::to_string(deg) + " deg about its first joint (" + joint +
                                       "): a bone there never translates; with a free bone above it, ik-chain " +
                                       std::to_string(handle) + " drags the chain instead"};
    }
  }
  execute("translate " + name, kPose, "transform " + std::to_string(handle), [&](SceneData& s) {
    PoseParams& p = s.pose;
    switch (r.kind) {
      case HandleKind::Point: p.point_translation[r.index] += d; break;
      case HandleKind::Bone: {
        // A bone's translation lives in its parent's frame; `d` is in world space.
        const Eigen::Quaterniond Rp = parent_world_rotation(s.rig.skeleton, p.bone_rotation, r.index);
        if (report.kind == DragKind::Rotated) p.bone_rotation[r.index] = (Rp.inverse() * turn * Rp * p.bone_rotation[r.index]).normalized();
        else p.bone_translation[r.index] += Rp.inverse() * d;  // a root's move, or an IK target (projected out when posed)
        break;
      }
      case HandleKind::CageVertex: {
        int base = 0;
        for (int c = 0; c < r.cage; ++c) base += s.rig.cages[c].mesh.num_vertices();
        p.cage_translation[base + r.index] += d;
        break;
      }
      case HandleKind::Region: p.region_transform[r.index].pretranslate(d); break;
    }
    if (solve && s.posing.dynamics) step_dynamics_in(s);
    else if (solve) solve_fast(s);
  });
  return report;
}

void Document::rotate_handle(int handle, const Eigen::Quaterniond& q_in) {
  if (!q_in.coeffs().allFinite() || q_in.norm() < 1e-12) throw Error("rotation is not a valid quaternion");
  const Eigen::Quaterniond q = q_in.normalized();
  const HandleRef r = handle_ref(s_.rig, handle);
  if (r.kind == HandleKind::CageVertex)
    throw Error("cage vertex handles only translate (" + handle_name(s_.rig, handle) + ")");
  const Eigen::Vector3d pivot = handle_pivot(handle);
  dyn_keep_ = false;
  execute("rotate " + handle_name(s_.rig, handle), kPose, "transform " + std::to_string(handle),
          [&](SceneData& s) {
            PoseParams& p = s.pose;
            switch (r.kind) {
              case HandleKind::Point: p.point_rotation[r.index] = (q * p.point_rotation[r.index]).normalized(); break;
              case HandleKind::Bone: {
                // World-space rotation q of the bone = parent * (Rp^-1 q Rp) * R_b in its parent's frame.
                const Eigen::Quaterniond Rp = parent_world_rotation(s.rig.skeleton, p.bone_rotation, r.index);
                p.bone_rotation[r.index] = (Rp.inverse() * q * Rp * p.bone_rotation[r.index]).normalized();
                break;
              }
              case HandleKind::Region: {
                Eigen::Affine3d& T = p.region_transform[r.index];
                const Eigen::Vector3d c = T * pivot;  // rotate about the region's current centroid
                T = Eigen::Translation3d(c) * q * Eigen::Translation3d(-c) * T;
                break;
              }
              case HandleKind::CageVertex: break;
            }
            if (s.posing.fast && s.posing.dynamics) step_dynamics_in(s);
            else if (s.posing.fast) solve_fast(s);
          });
}

void Document::set_bone_twist_stretch(int bone, const BoneTwistStretch& ts) {
  const int nb = s_.rig.skeleton.num_bones();
  if (bone < 0 || bone >= nb) throw Error("no bone " + std::to_string(bone) + " (the rig has " + std::to_string(nb) + ")");
  if (!std::isfinite(ts.twist) || !std::isfinite(ts.stretch) || !std::isfinite(ts.twist_start))
    throw Error("twist and stretch must be finite");
  if (!(ts.stretch > 0)) throw Error("a bone's stretch must be positive, got " + std::to_string(ts.stretch));
  execute("twist/stretch " + handle_name(s_.rig, num_point_handles(s_.rig) + bone), kPose, "twist/stretch " + std::to_string(bone), [&](SceneData& s) {
    if (s.pose.bone_twist_stretch.size() != static_cast<size_t>(nb)) s.pose.bone_twist_stretch.resize(nb);
    s.pose.bone_twist_stretch[bone] = ts;
  });
}

void Document::reset_pose() {
  PoseParams rest = fit_pose_params(s_.rig, {});
  execute("reset pose", kPose, "", [&](SceneData& s) { s.pose = std::move(rest); });
}

std::vector<HandleConstraint> Document::handle_states() const {
  if (static_cast<int>(s_.posing.states.size()) == num_handles()) return s_.posing.states;
  return default_constraint_states(s_.rig);
}

void Document::solve_fast(SceneData& s) {
  if (!has_weights()) return;
  if (!fast_) fast_ = std::make_unique<FastPosing>();
  const std::vector<HandleConstraint> states =
      static_cast<int>(s.posing.states.size()) == dfm::num_handles(s.rig) ? s.posing.states : default_constraint_states(s.rig);
  last_fast_ = fast_->solve(s.rig, s.surface.V, s.surface.F, skin_weights(), states, s.posing.iterations, s.pose);
}

void Document::set_posing(const PosingSettings& p) {
  if (p.iterations < 1 || p.iterations > 1000) throw Error("FAST iterations must be in [1, 1000]");
  if (!(p.dt > 0 && p.dt <= 1)) throw Error("dynamics: the time step must be in (0, 1] s");
  if (!(p.damping >= 0 && std::isfinite(p.damping))) throw Error("dynamics: damping must be >= 0");
  if (!(p.density > 0 && std::isfinite(p.density))) throw Error("dynamics: density must be > 0");
  if (!p.states.empty() && static_cast<int>(p.states.size()) != num_handles())
    throw Error("handle states: " + std::to_string(p.states.size()) + " for " + std::to_string(num_handles()) + " handles");
  execute("posing settings", kPose, "", [&](SceneData& s) {
    s.posing = p;
    if (s.posing.fast) solve_fast(s);
  });
}

void Document::set_handle_state(int handle, HandleConstraint state) {
  if (handle < 0 || handle >= num_handles()) throw Error("no handle " + std::to_string(handle));
  PosingSettings p = s_.posing;
  p.states = handle_states();
  p.states[handle] = state;
  execute(std::string("set ") + handle_name(s_.rig, handle) + " " + constraint_state_name(state), kPose, "",
          [&](SceneData& s) {
            s.posing = p;
            if (s.posing.fast) solve_fast(s);
          });
}

DragReport Document::drag_handle(int handle, const Eigen::Vector3d& delta) {
  if (!has_weights()) throw Error("drag: bind first (FAST solves with the weights)");
  return move_handle(handle, delta, true);
}

// ---- keys ------------------------------------------------------------------------------------------

void Document::set_key(double t) {
  if (!std::isfinite(t)) throw Error("key time is not finite");
  const int at = key_at(t);
  execute(at >= 0 ? "replace key" : "set key", kKeys, "", [&](SceneData& s) {
    if (at >= 0) {
      s.keys[at].params = s.pose;
      s.keys[at].mesh = TriMesh{};  // a mesh key replaced by a pose key
      s.keys[at].mesh_path.clear();
      return;
    }
    SceneKey k{t, s.pose, {}, {}};
    auto it = std::lower_bound(s.keys.begin(), s.keys.end(), t, [](const SceneKey& a, double x) { return a.time < x; });
    s.keys.insert(it, std::move(k));
  });
}

void Document::key_mesh(const TriMesh& mesh, const std::string& path, double t) {
  if (!std::isfinite(t)) throw Error("key time is not finite");
  if (mesh.num_vertices() == 0 || mesh.num_faces() == 0) throw Error(path + ": mesh has no triangles");
  TriMesh m{mesh.V, mesh.F, {}};  // positions and triangles: the manifold needs no normals
  check_transition_key(m, path);  // throws naming the file before anything changes
  const int at = key_at(t);
  const std::string name = "key mesh " + std::filesystem::path(path).filename().string();
  execute(at >= 0 ? "replace key (" + name + ")" : name, kKeys, "", [&](SceneData& s) {
    if (at >= 0) {
      s.keys[at].mesh = std::move(m);
      s.keys[at].mesh_path = path;
      return;
    }
    SceneKey k{t, fit_pose_params(s.rig, {}), std::move(m), path};
    auto it = std::lower_bound(s.keys.begin(), s.keys.end(), t, [](const SceneKey& a, double x) { return a.time < x; });
    s.keys.insert(it, std::move(k));
  });
}

void Document::key_mesh_file(const std::string& path, double t) {
  if (!std::isfinite(t)) throw Error("key time is not finite");
  key_mesh(read_surface(path), path, t);
}

void Document::delete_key(int index) {
  if (index < 0 || index >= static_cast<int>(s_.keys.size())) throw Error("no key " + std::to_string(index));
  execute("delete key", kKeys, "", [&](SceneData& s) { s.keys.erase(s.keys.begin() + index); });
}

void Document::set_key_inbetween(int index, InbetweenMethod method) {
  if (index < 0 || index >= static_cast<int>(s_.keys.size())) throw Error("no key " + std::to_string(index));
  execute(std::string("in-between: ") + inbetween_method_name(method), kKeys, "",
          [&](SceneData& s) { s.keys[index].inbetween = method; });
}

void Document::set_key_pairs(int index, const Eigen::MatrixXd& pairs) {
  if (index < 0 || index + 1 >= static_cast<int>(s_.keys.size()))
    throw Error("picked pairs join a key to the next: no key after key " + std::to_string(index));
  if (pairs.rows() > 0 && pairs.cols() != 6) throw Error("a picked pair needs 6 numbers (x0 y0 z0 x1 y1 z1)");
  if (!pairs.allFinite()) throw Error("a picked pair's coordinate is not finite");
  const Eigen::MatrixXd p = pairs.rows() > 0 ? pairs : Eigen::MatrixXd(0, 6);
  execute(p.rows() > 0 ? "picked pairs" : "clear picked pairs", kKeys, "", [&](SceneData& s) { s.keys[index].pairs_to_next = p; });
}

void Document::move_key(int index, double t) {
  if (index < 0 || index >= static_cast<int>(s_.keys.size())) throw Error("no key " + std::to_string(index));
  if (!std::isfinite(t)) throw Error("key time is not finite");
  const int other = key_at(t);
  if (other >= 0 && other != index) throw Error("a key already sits at time " + std::to_string(t));
  execute("move key", kKeys, "move key", [&](SceneData& s) {
    s.keys[index].time = t;
    std::stable_sort(s.keys.begin(), s.keys.end(), [](const SceneKey& a, const SceneKey& b) { return a.time < b.time; });
  });
}

void Document::go_to_key(int index) {
  if (index < 0 || index >= static_cast<int>(s_.keys.size())) throw Error("no key " + std::to_string(index));
  if (s_.keys[index].is_mesh())
    throw Error("key " + std::to_string(index) + " is a mesh key (" + s_.keys[index].mesh_path + "): it has no pose");
  PoseParams p = s_.keys[index].params;
  execute("go to key", kPose, "", [&](SceneData& s) { s.pose = std::move(p); });
}

}  // namespace dfm
