// A space-time drag's frame next to plain posing's, on the keyed default scene (issue 35: "a drag
// redraws at the rate of plain posing"). CPU side of one frame each, as the editor does it:
//   posing: the document's rotate of a bone + the surface skinned with the pose (the editor skins on
//           the GPU; the CPU skin here is an upper bound);
//   drag:   the document's set_space_time_edit + the manifold builder's replay + the 4D vertex normals
//           + the GPU slicer's vertex upload (floats) + the shown interval's records from its kept
//           topology (scene_view.cpp: same tetrahedra and times, same cut).
// Now: the replay rewrites one of two edited manifolds in turn (the builder's: V copied from the
// built one, the tetrahedra kept) and writes only the region's rows, a translation-only drag moving the
// free vertices by the reach times the translation (manifold_edit.h); the normals re-sum the stars
// around the region from a plan made once per region; the view's same-cut check is the builder's
// positions_only (no retime) instead of comparing the tetrahedra.
// Before, in the same process and on the same drag: a copy of the built manifold, the cache's check,
// a back substitution (ManifoldEditOptions::linear_translation off) into a copy of V, the normals
// found by scanning the edit's window, and the same-cut check comparing tetrahedra, times and t. Every frame's vertices are compared (the reach's rounding
// against the back substitution's) and the normals checked bit for bit.
// Also the drag's first frame (select the region and factor: once per region).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "core/anim/interval_slice.h"
#include "core/anim/manifold_edit.h"
#include "core/anim/manifold_edit_region.h"
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
static double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(q * (v.size() - 1))];
}
static double median(const std::vector<double>& v) { return quantile(v, 0.5); }

namespace {

// The slicer upload's CPU side (float conversion of every vertex and normal).
void upload_floats(const AnimationManifold& m, const Eigen::MatrixXd& N, std::vector<float>& pos, std::vector<float>& nrm) {
  pos.resize(m.V.size()), nrm.resize(m.V.size());
  for (Eigen::Index i = 0; i < m.V.size(); ++i) pos[i] = static_cast<float>(m.V.data()[i]);
  for (int v = 0; v < m.num_vertices(); ++v)
    for (int d = 0; d < 4; ++d) nrm[4 * v + d] = static_cast<float>(N(v, d));
}

struct Parts {
  std::vector<double> replay, normals, upload, records, total;
  void add(double r, double n, double u, double c) {
    replay.push_back(r), normals.push_back(n), upload.push_back(u), records.push_back(c), total.push_back(r + n + u + c);
  }
  // The parts' medians summed: a frame without the preemptions a shared machine adds (the totals'
  // upper quartile shows them).
  double typical() const { return median(replay) + median(normals) + median(upload) + median(records); }
  void print(const char* what) const {
    std::printf("%s: %.2f ms = medians of edit + replay %.2f, 4D normals %.2f, slicer upload's floats %.2f, same-cut "
                "check + interval records %.2f (whole frames: median %.2f, quartiles %.2f-%.2f)\n",
                what, typical(), median(replay), median(normals), median(upload), median(records), median(total),
                quantile(total, 0.25), quantile(total, 0.75));
  }
};

}  // namespace

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
  const int frames = 200;

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

  SpaceTimeEdit e = doc.space_time_edits().back();
  e.handle = {{1.0267, 0.8326, -0.017}, 1.0};
  // Before: the editor as the replay made it, every drag a back substitution.
  ManifoldEditOptions before_options;
  before_options.weights = e.weights;
  before_options.time_scale = e.time_scale;
  before_options.preserve_volume = e.preserve_volume;
  before_options.linear_translation = false;
  const ManifoldEditor before_editor(base, select_edit_region(base, e.region, e.handle), e.handle.point, before_options);
  std::printf("the drag's region: %d vertices, %d handle vertices\n",
              static_cast<int>(before_editor.selection().region.size()), static_cast<int>(before_editor.selection().handle.size()));

  SpaceTimeEditCache cache;
  AnimationManifold edited[2] = {base, base};  // the builder's two in turn
  Eigen::MatrixXd edited_normals[2];
  Parts now, before;
  std::vector<double> edit_ms;
  double first_ms = 0, max_diff = 0, max_move = 0;
  IntervalSlice kept;  // the interval ending at t = 1, cut on the first frame
  const AnimationManifold* previous = nullptr;
  bool previous_positions_only = false;
  std::vector<float> pos, nrm;
  doc.begin_gesture();
  for (int f = 0; f <= frames; ++f) {
    e.move = Eigen::Vector3d(-0.05, 0.25, 0.1) * (f + 1) / (frames + 1);
    auto t = Clock::now();
    doc.set_space_time_edit(0, e);
    const double ed = ms_since(t);
    const std::vector<SpaceTimeEdit>& edits = doc.space_time_edits();

    // Now.
    t = Clock::now();
    AnimationManifold& m = edited[f % 2];
    m.V = base.V;
    const auto notes = apply_space_time_edits(m, edits, &cache);
    const double r = ms_since(t);
    t = Clock::now();
    Eigen::MatrixXd& N = edited_normals[f % 2];
    edited_vertex_normals(m, base.V, base_normals, edits, cache, N);
    const double n = ms_since(t);
    t = Clock::now();
    if (!previous) validate_manifold(m, "GPU slice manifold");  // a full upload's check: only on a new cut
    upload_floats(m, N, pos, nrm);
    const double up = ms_since(t);
    t = Clock::now();
    // The builder knows (positions_only): no retime in this replay or the last, the same built manifold.
    bool same_cut = previous && previous_positions_only && cache.written_valid;
    previous_positions_only = cache.written_valid;
    if (!same_cut) kept = build_interval_slice(m, N, 0.8, 1.0);
    gl::IntervalRecords records = gl::interval_records(kept, m, N);
    const double rec = ms_since(t);
    if (!notes.empty() || records.vertices.empty()) return std::printf("%s\n", notes.empty() ? "?" : notes[0].c_str()), 1;
    if (f == 0) {
      first_ms = ed + r + n + up + rec;
      previous = &m;
      continue;
    }
    now.add(ed + r, n, up, rec);

    // Before.
    t = Clock::now();
    AnimationManifold mb = base;
    if (mb.V != base.V) return 1;  // the cache's check of its input
    ManifoldDrag d;
    d.translation = e.move;
    mb.V = before_editor.drag(d);
    const double rb = ms_since(t);
    t = Clock::now();
    const Eigen::MatrixXd Nb = edited_vertex_normals(mb, base.V, base_normals, edits);
    const double nb = ms_since(t);
    t = Clock::now();
    upload_floats(mb, Nb, pos, nrm);
    const double ub = ms_since(t);
    t = Clock::now();
    same_cut = previous->times == mb.times && previous->V.col(3) == mb.V.col(3) && previous->T == mb.T;
    if (!same_cut) return std::printf("the cut changed\n"), 1;
    if (previous->T != m.T || previous->V.col(3) != m.V.col(3)) return std::printf("the replay changed the cut\n"), 1;
    records = gl::interval_records(kept, mb, Nb);
    const double cb = ms_since(t);
    before.add(ed + rb, nb, ub, cb);
    edit_ms.push_back(ed);

    max_diff = std::max(max_diff, (m.V - mb.V).cwiseAbs().maxCoeff());
    max_move = std::max(max_move, e.move.norm());
    // The back substitution's rounding moves a normal by as little: the normals are checked against
    // the scan's on the same vertices, bit for bit.
    Eigen::MatrixXd Nm;
    edited_vertex_normals(mb, base.V, base_normals, edits, cache, Nm);
    if (Nm != Nb) return std::printf("the planned normals differ from the window scan's\n"), 1;
    previous = &m;
  }
  doc.end_gesture();
  if (edited_normals[frames % 2] != manifold_vertex_normals(edited[frames % 2]))
    return std::printf("the last frame's normals are not manifold_vertex_normals'\n"), 1;
  std::printf("normals plan: %zu affected vertices, %zu tetrahedra\n", cache.plan_affected.size(), cache.plan_tets.size());
  std::printf("plain posing frame (rotate + CPU skin): median %.2f ms\n", median(pose_ms));
  std::printf("space-time drag, first frame (select + factor + replay + normals + upload + interval): %.1f ms\n", first_ms);
  std::printf("the document's set_space_time_edit: median %.3f ms (in both)\n", median(edit_ms));
  now.print("space-time drag frame now");
  before.print("the same frame before   ");
  std::printf("drag frame / plain posing: %.1f now, %.1f before; before / now %.1f\n", now.typical() / median(pose_ms),
              before.typical() / median(pose_ms), before.typical() / now.typical());
  std::printf("largest vertex difference now - before: %.2e (moves up to %.3f)\n", max_diff, max_move);
  std::printf("undo steps for the %d-frame drag: %s\n", frames + 1, doc.undo_name().c_str());
  return 0;
}
