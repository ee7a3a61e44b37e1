// A space-time drag's frame next to plain posing's, on the keyed default scene (issue 35: "a drag
// redraws at the rate of plain posing"). CPU side of one frame each, as the editor does it:
//   posing: the document's rotate of a bone + the surface skinned with the pose (the editor skins on
//           the GPU; the CPU skin here is an upper bound);
//   drag:   the document's set_space_time_edit + the manifold builder's replay (copy of the built
//           manifold, back substitution on the cached factorisation) + the 4D vertex normals the view
//           uploads (the window's rows only) + the viewport's interval topology + the slice at the
//           current time (the editor slices on the GPU).
// Also the drag's first frame (select the region and factor: once per region).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "core/anim/interval_slice.h"
#include "core/anim/manifold_frame.h"
#include "core/anim/manifold_normals.h"
#include "core/anim/manifold_sequence.h"
#include "core/scene/bind_document.h"
#include "core/scene/key_surfaces.h"
#include "core/scene/script.h"
#include "core/scene/space_time_edit.h"

using namespace dfm;
using Clock = std::chrono::steady_clock;

static double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }
static double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

int main() {
  Document doc;
  doc.load_scene(std::string(DFM_SOURCE_DIR) + "/assets/default.scene.json");
  run_bind_blocking(doc);
  run_script(doc,
             parse_script("fast off\nset-key 0\nselect l_upper_arm\nrotate 40 0 0 1\nset-key 1\nrotate -60 0 0 1\n"
                          "set-key 2\nset-time 1\nedit-region 0.95 0.75 0 0.5 0.4 1.6\n",
                          "bench"),
             "bench");
  const AnimationManifold base = build_manifold_sequence(key_surfaces(doc));
  const Eigen::MatrixXd base_normals = manifold_vertex_normals(base);
  std::printf("keyed default scene: %d surface vertices, manifold %d vertices, %d tets, %d layers\n",
              doc.surface().num_vertices(), base.num_vertices(), base.num_tets(), base.num_layers());
  const int frames = 60;

  // Plain posing.
  const SkinBinding binding = pose_binding(doc);
  std::vector<double> pose_ms;
  const int bone = 5;  // l_upper_arm (3 points, then spine, neck)
  for (int f = 0; f < frames; ++f) {
    const auto t = Clock::now();
    doc.begin_gesture();
    doc.rotate_handle(bone, Eigen::Quaterniond(Eigen::AngleAxisd(0.002, Eigen::Vector3d::UnitZ())));
    doc.end_gesture();
    const Eigen::MatrixXd V = skin_params(doc, binding, doc.pose_params());
    pose_ms.push_back(ms_since(t));
    if (V.rows() == 0) return 1;
  }

  // Space-time drag.
  SpaceTimeEdit e = doc.space_time_edits().back();
  e.handle = {{1.0267, 0.8326, -0.017}, 1.0};
  SpaceTimeEditCache cache;
  std::vector<double> drag_ms, replay_ms, normals_ms, interval_ms;
  double first_ms = 0;
  doc.begin_gesture();
  for (int f = 0; f <= frames; ++f) {
    e.move = Eigen::Vector3d(-0.05, 0.25, 0.1) * (f + 1) / (frames + 1);
    const auto t = Clock::now();
    doc.set_space_time_edit(0, e);
    AnimationManifold m = base;
    const auto notes = apply_space_time_edits(m, doc.space_time_edits(), &cache);
    const double r = ms_since(t);
    const Eigen::MatrixXd N = edited_vertex_normals(m, base_normals, doc.space_time_edits());
    const double n = ms_since(t) - r;
    // The viewport's interval cache starts over on a new manifold: the interval ending at t = 1 again.
    const IntervalSlice interval = build_interval_slice(m, N, 0.8, 1.0);
    const double iv = ms_since(t) - r - n;
    const TriMesh slice = manifold_frame(m, doc.time()).mesh;
    if (!notes.empty() || N.rows() == 0 || slice.num_vertices() == 0 || interval.num_vertices() == 0) return std::printf("%s\n", notes.empty() ? "?" : notes[0].c_str()), 1;
    if (f == 0) first_ms = ms_since(t);
    else drag_ms.push_back(ms_since(t)), replay_ms.push_back(r), normals_ms.push_back(n), interval_ms.push_back(iv);
  }
  doc.end_gesture();
  std::printf("plain posing frame (rotate + CPU skin): median %.2f ms\n", median(pose_ms));
  std::printf("space-time drag, first frame (select + factor + replay + normals + slice): %.1f ms\n", first_ms);
  std::printf("space-time drag frame: median %.2f ms (edit + copy + back substitution %.2f ms, 4D normals %.2f ms, "
              "the viewport's interval topology %.2f ms, CPU slice the rest)\n",
              median(drag_ms), median(replay_ms), median(normals_ms), median(interval_ms));
  std::printf("undo steps for the %d-frame drag: %s\n", frames + 1, doc.undo_name().c_str());
  return 0;
}
