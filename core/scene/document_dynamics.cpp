// Document commands that simulate: live dynamics drags and Simulate (document.h; Jacobson 2013, 7.7).
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/scene/document.h"
#include "core/scene/document_parts.h"
#include "core/scene/key_surfaces.h"
#include "core/util/error.h"

namespace dfm {

namespace {
constexpr double kSettledSpeed = 1e-3;  // diagonals per second: below, the motion is not visible
constexpr double kMaxSettleSeconds = 30;  // simulated: a settle always ends
}  // namespace

FastDynamicsOptions Document::dynamics_options(const PosingSettings& p) const {
  FastDynamicsOptions o;
  o.dt = p.dt;
  o.damping = p.damping;
  o.iterations = p.iterations;
  return o;
}

void Document::step_dynamics_in(SceneData& s) {
  if (!has_weights()) return;
  if (!dyn_live_ || !dyn_) {
    DynamicsInputs in{surface_weights_revision_, surface_rig_revision_, s.posing};
    in.posing.states = handle_states();
    in.posing.fast = true;  // only what the simulation reads
    if (dyn_ && in == dyn_inputs_) {
      dyn_->restart(s.rig, s.pose);
    } else {
      dyn_ = std::make_unique<PoseDynamics>(s.rig, s.surface.V, s.surface.F, skin_weights(), in.posing.states,
                                            dynamics_options(s.posing), s.posing.density, s.pose);
      dyn_inputs_ = in;
    }
  }
  dyn_->step(s.rig, s.pose);
  dyn_keep_ = true;
}

bool Document::step_dynamics() {
  if (!dyn_live_ || !dyn_) return false;
  dyn_->step(s_.rig, s_.pose);
  touch_top_step();  // the drag's step is the top one: any other edit ended the simulation
  dyn_keep_ = dyn_->relative_speed() >= kSettledSpeed && dyn_->steps() * s_.posing.dt < kMaxSettleSeconds;
  after_change(kPose);
  return dyn_live_;
}

int Document::settle_dynamics(int max_steps) {
  int n = 0;
  while (dyn_live_ && (max_steps < 0 || n < max_steps)) step_dynamics(), ++n;
  return n;
}

int Document::simulate(double fps, double from, double to) {
  if (!has_weights()) throw Error("simulate: bind first (the dynamics solve with the weights)");
  if (!(fps > 0 && fps <= 1000)) throw Error("simulate: frames per second must be in (0, 1000]");
  std::vector<double> pose_times;
  for (const SceneKey& k : s_.keys)
    if (!k.is_mesh()) pose_times.push_back(k.time);
  if (pose_times.empty()) throw Error("simulate: no pose keys to simulate");
  if (std::isnan(from)) from = s_.keys.front().time;
  if (std::isnan(to)) to = s_.keys.back().time;
  if (!std::isfinite(from) || !std::isfinite(to) || !(to > from))
    throw Error("simulate: the range must be finite with FROM before TO");
  const int n = static_cast<int>(std::lround((to - from) * fps));
  if (n < 1) throw Error("simulate: the range holds less than one frame at " + std::to_string(fps) + " fps");
  if (n > 100000) throw Error("simulate: more than 100000 frames");
  const double last = from + n / fps, eps = 1e-9 * std::max(1.0, std::abs(last));
  const double lo = from - eps, hi = std::max(to, last) + eps;
  for (const SceneKey& k : s_.keys)
    if (k.is_mesh() && k.time >= lo && k.time <= hi)
      throw Error("simulate: the mesh key at " + std::to_string(k.time) + " has no handles to simulate");

  // The constraints at every frame, from the keys as they are now.
  std::vector<SceneKey> frames(n + 1);
  for (int i = 0; i <= n; ++i) {
    frames[i].time = from + i / fps;
    frames[i].params = animation_params(*this, frames[i].time);
  }
  const std::vector<HandleConstraint> states = handle_states();
  if (!fast_) fast_ = std::make_unique<FastPosing>();
  last_fast_ = fast_->solve(s_.rig, s_.surface.V, s_.surface.F, skin_weights(), states, s_.posing.iterations, frames[0].params);
  PosingSettings p = s_.posing;
  p.dt = 1 / fps;
  PoseDynamics dyn(s_.rig, s_.surface.V, s_.surface.F, skin_weights(), states, dynamics_options(p), p.density,
                   frames[0].params);
  for (int i = 1; i <= n; ++i) dyn.step(s_.rig, frames[i].params);

  execute("simulate", kKeys, "", [&](SceneData& s) {
    s.keys.erase(std::remove_if(s.keys.begin(), s.keys.end(), [&](const SceneKey& k) { return k.time >= lo && k.time <= hi; }),
                 s.keys.end());
    for (SceneKey& f : frames) s.keys.push_back(std::move(f));
    std::stable_sort(s.keys.begin(), s.keys.end(), [](const SceneKey& a, const SceneKey& b) { return a.time < b.time; });
  });
  return n + 1;
}

}  // namespace dfm
