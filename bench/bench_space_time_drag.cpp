// A space-time drag's frame next to plain posing's, on the keyed default scene (issue 35: "a drag
// redraws at the rate of plain posing"). CPU side of one frame each, as the editor does it:
//   posing: the document's rotate of a bone + the surface skinned with the pose (the editor skins on
//           the GPU; the CPU skin here is an upper bound);
//   drag:   the document's set_space_time_edit + the manifold builder's replay (copy of the built
//           manifold, back substitution on the cached factorisation) + the 4D vertex normals of the
//           moved vertices' stars + the GPU slicer's vertex upload (floats) + the shown interval's records
//           from its kept topology (scene_view.cpp: same tetrahedra and times, same cut), and, for
//           comparison, the same frame as before (normals over the whole window, topology cut again).
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
#include "render/interval_records.h"

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

  // Space-time drag. The editor's CPU per frame: the edit + replay (copy, back substitution), the 4D
  // normals of the moved vertices' stars, the GPU slicer upload's CPU side (validate + float
  // conversion), and for the interval on display either its topology cut again (before) or, the
  // tetrahedra and times unchanged, its records re-made from the kept topology (now).
  SpaceTimeEdit e = doc.space_time_edits().back();
  e.handle = {{1.0267, 0.8326, -0.017}, 1.0};
  SpaceTimeEditCache cache;
  std::vector<double> now_ms, before_ms, replay_ms, normals_ms, window_ms, upload_ms, records_ms, cut_ms, validate_ms;
  double first_ms = 0;
  IntervalSlice kept;  // the interval ending at t = 1, cut on the first frame
  const AnimationManifold* previous = nullptr;
  AnimationManifold last;
  doc.begin_gesture();
  for (int f = 0; f <= frames; ++f) {
    e.move = Eigen::Vector3d(-0.05, 0.25, 0.1) * (f + 1) / (frames + 1);
    auto t = Clock::now();
    doc.set_space_time_edit(0, e);
    AnimationManifold m = base;
    const auto notes = apply_space_time_edits(m, doc.space_time_edits(), &cache);
    const double r = ms_since(t);
    t = Clock::now();
    const Eigen::MatrixXd N = edited_vertex_normals(m, base.V, base_normals, doc.space_time_edits());
    const double n = ms_since(t);
    t = Clock::now();
    if (!previous) validate_manifold(m, "GPU slice manifold");  // a full upload's check: only on a new cut
    std::vector<float> pos(m.V.size()), nrm(m.V.size());
    for (Eigen::Index i = 0; i < m.V.size(); ++i) pos[i] = static_cast<float>(m.V.data()[i]);
    for (int v = 0; v < m.num_vertices(); ++v)
      for (int d = 0; d < 4; ++d) nrm[4 * v + d] = static_cast<float>(N(v, d));
    const double up = ms_since(t);
    t = Clock::now();
    const bool same_cut = previous && previous->times == m.times && previous->V.col(3) == m.V.col(3) && previous->T == m.T;
    if (!same_cut) kept = build_interval_slice(m, N, 0.8, 1.0);
    const gl::IntervalRecords records = gl::interval_records(kept, m, N);
    const double rec = ms_since(t);
    // Before: the normals over the whole window and the topology cut again (outside the frame's time).
    t = Clock::now();
    Eigen::MatrixXd Nw = base_normals;
    int first = -1, last_slab = -1;
    for (int s = 0; s < m.num_slabs(); ++s)
      if (m.times[s + 1] >= e.region.t0 && m.times[s] <= e.region.t1) last_slab = s, first = first < 0 ? s : first;
    const VertexNormalSource src(m, nullptr, m.slab_offsets[first], m.slab_offsets[last_slab + 1]);
    for (int v = 0; v < m.num_vertices(); ++v)
      if (m.V(v, 3) >= e.region.t0 && m.V(v, 3) <= e.region.t1) Nw.row(v) = src(v).transpose();
    const double w = ms_since(t);
    t = Clock::now();
    const IntervalSlice cut = build_interval_slice(m, N, 0.8, 1.0);
    const double c = ms_since(t);
    t = Clock::now();
    validate_manifold(m, "GPU slice manifold");
    const double val = ms_since(t);
    if (Nw != N) return std::printf("the window's normals differ from the moved vertices' stars'\n"), 1;
    if (cut.edges != kept.edges || cut.F != kept.F) return std::printf("the kept topology differs from a new cut\n"), 1;
    if (!notes.empty() || records.vertices.empty()) return std::printf("%s\n", notes.empty() ? "?" : notes[0].c_str()), 1;
    last = std::move(m);
    previous = &last;
    if (f == 0) {
      first_ms = r + n + up + rec;
      continue;
    }
    replay_ms.push_back(r), normals_ms.push_back(n), upload_ms.push_back(up), records_ms.push_back(rec);
    window_ms.push_back(w), cut_ms.push_back(c), validate_ms.push_back(val);
    now_ms.push_back(r + n + up + rec);
    before_ms.push_back(r + w + val + up + c + rec);
  }
  doc.end_gesture();
  std::printf("plain posing frame (rotate + CPU skin): median %.2f ms\n", median(pose_ms));
  std::printf("space-time drag, first frame (select + factor + replay + normals + upload + interval): %.1f ms\n", first_ms);
  std::printf("space-time drag frame: median %.2f ms: edit + copy + back substitution %.2f, 4D normals of the moved "
              "vertices' stars %.2f, slicer vertex upload's floats %.2f, interval records from the kept "
              "topology %.2f\n", median(now_ms), median(replay_ms), median(normals_ms), median(upload_ms),
              median(records_ms));
  std::printf("the same frame as before (normals over the whole window %.2f, the full upload's validate %.2f, topology "
              "cut again %.2f): median %.2f ms\n", median(window_ms), median(validate_ms), median(cut_ms), median(before_ms));
  std::printf("drag frame / plain posing: %.1f now, %.1f before\n", median(now_ms) / median(pose_ms),
              median(before_ms) / median(pose_ms));
  std::printf("undo steps for the %d-frame drag: %s\n", frames + 1, doc.undo_name().c_str());
  return 0;
}
