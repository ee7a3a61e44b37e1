// Batch and test entry points of the editor: --play-frames (playback against posing, by stage),
// --drag-frames (a space-time drag against posing), --ui
// (initial tool and view state), and waiting for the Shape space panel's worker before a screenshot.
// A script's bind with its frames is batch_runner.h's.
#include "app/editor/editor.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

#include "app/editor/shape_space_panel.h"
#include "core/util/error.h"

namespace dfm::editor {

// Plays the timeline for a number of frames, each one fully drawn and finished (glFinish), and prints
// the frame times: what an artist sees while the animation plays. The stage split (ImGui layout and
// input, deform = slice or skin, scene draw, ImGui draw) is measured with glFinish between stages.
// A frame that shows no vertex while the document has a surface is counted: it is a bug.
// The frame halfway through the keys: its vertex and triangle counts (a transition's slice is the
// lattice's, not a key's).
void Editor::print_mid_frame() {
  if (doc_.keys().size() < 2) return;
  const double mid = 0.5 * (doc_.keys().front().time + doc_.keys().back().time);
  doc_.set_time(mid);
  tick(0);
  render_frame();
  std::printf("play-frames: at t = %.3f the frame shows %d vertices, %d triangles (%s)\n", mid, view_->display_vertex_count(),
              view_->display_face_count(), view_->showing_slice() ? "manifold slice" : "skinned");
  std::fflush(stdout);
}

double Editor::FrameTimes::mean() const {
  double sum = 0;
  for (double m : ms) sum += m;
  return ms.empty() ? 0.0 : sum / double(ms.size());
}

Editor::FrameStages Editor::FrameTimes::mean_stages() const {
  const double n = std::max<double>(1, double(ms.size()));
  return {sum.ui / n, sum.sync / n, sum.scene / n, sum.imgui / n};
}

std::string Editor::FrameTimes::summary() const {
  if (ms.empty()) return "no frames";
  std::vector<double> s = ms;
  std::sort(s.begin(), s.end());
  char buf[160];
  std::snprintf(buf, sizeof buf, "mean %.2f ms, median %.2f ms, p95 %.2f ms, max %.2f ms", mean(), s[s.size() / 2],
                s[std::min(s.size() - 1, size_t(0.95 * s.size()))], s.back());
  return buf;
}

// Each frame: before(i), drawn, finished (glFinish), swapped, events polled, after(measured). The
// first three frames compile shaders and upload, so they are not measured.
Editor::FrameTimes Editor::timed_frames(int frames, const std::function<void(int)>& before,
                                        const std::function<void(bool)>& after) {
  FrameTimes times;
  profile_stages_ = true;
  for (int i = 0; i < frames + 3; ++i) {
    const double t0 = glfwGetTime();
    before(i);
    render_frame();
    glFinish();
    present_frame();
    glfwPollEvents();
    const bool measured = i >= 3;
    if (measured) {
      times.ms.push_back(1000.0 * (glfwGetTime() - t0));
      FrameStages& st = times.sum;
      st.ui += stages_.ui, st.sync += stages_.sync, st.scene += stages_.scene, st.imgui += stages_.imgui;
    }
    if (after) after(measured);
  }
  profile_stages_ = false;
  return times;
}

// Posing: the current pose skinned again and shown every frame; still: the view only redrawn.
Editor::FrameTimes Editor::posed_frames(int frames, bool reskin) {
  return timed_frames(frames, [&](int) {
    if (reskin) view_->show_pose();
  });
}

void Editor::play_benchmark(int frames) {
  wait_for_manifold();  // a transition plays once it is built, as an artist would see it
  playing_ = true;
  loop_ = true;
  int empty = 0, cached = 0;
  double first_empty_t = 0;
  const int built0 = view_->intervals_built();
  const double build_ms0 = view_->interval_build_ms();
  const FrameTimes play = timed_frames(frames, [&](int) { tick(1.0 / 30.0); }, [&](bool measured) {
    cached += measured && view_->slice_from_cache();
    if (view_->display_vertex_count() == 0 && doc_.surface().num_vertices() > 0 && empty++ == 0) first_empty_t = doc_.time();
  });
  playing_ = false;
  const FrameStages st = play.mean_stages();
  std::printf("play-frames: %d frames, %d vertices shown (%s), %s\n", int(play.ms.size()), view_->display_vertex_count(),
              view_->showing_slice() ? "manifold slice" : "skinned", play.summary().c_str());
  std::printf("play-frames: mean per stage: ui %.2f ms, deform %.2f ms, scene draw %.2f ms, imgui draw %.2f ms\n", st.ui,
              st.sync, st.scene, st.imgui);
  std::printf("play-frames: %d of %d frames drawn from the interval cache, %d interval topologies built in %.1f ms "
              "(%d distinct vertex times)\n",
              cached, int(play.ms.size()), view_->intervals_built() - built0, view_->interval_build_ms() - build_ms0,
              view_->vertex_time_count());
  if (empty) std::printf("play-frames: %d frames showed no vertices (first at t=%.6g)\n", empty, first_empty_t);
  // The baseline in the same process: as many frames of the current pose, not playing. Posing skins
  // the pose again every frame (what an edit or a drag costs); a still frame only redraws it.
  view_->show_pose();
  const FrameTimes posed = posed_frames(frames, true), still = posed_frames(frames, false);
  if (!view_->showing_slice() && posed.mean() > 0) {
    const FrameStages p = posed.mean_stages(), q = still.mean_stages();
    std::printf("play-frames: posed mean per stage: ui %.2f ms, deform %.2f ms, scene draw %.2f ms, imgui draw %.2f ms\n",
                p.ui, p.sync, p.scene, p.imgui);
    std::printf("play-frames: still posed frame (not skinned again) mean %.2f ms (deform %.2f ms, scene draw %.2f ms)\n",
                still.mean(), q.sync, q.scene);
    std::printf("play-frames: playback mean %.2f ms; posed mean %.2f ms; ratio %.2f\n", play.mean(), posed.mean(),
                play.mean() / posed.mean());
  } else {
    std::printf("play-frames: no posed baseline (the scene has no skinned pose to show)\n");
  }
  std::fflush(stdout);
  print_mid_frame();
}

// Drags the document's last space-time edit for `frames` frames, as the Space-time tool's drag does
// (the edit's move set in one gesture, the manifold's slice at the handle's time redrawn), each frame
// drawn and finished, then as many frames of the edited slice standing still and of posing, in the
// same process (issue 35: "a drag redraws at the rate of plain posing"). The move sweeps a circle of 5%
// of the surface's diagonal; the drag is undone.
void Editor::drag_benchmark(int frames) {
  wait_for_manifold();
  if (doc_.space_time_edits().empty()) {
    std::printf("drag-frames: no space-time edit to drag (a script's edit-region and edit-drag make one)\n");
    std::fflush(stdout);
    return;
  }
  const int index = static_cast<int>(doc_.space_time_edits().size()) - 1;
  const SpaceTimeEdit e0 = doc_.space_time_edits()[index];
  doc_.set_time(e0.handle.time);
  const Eigen::AlignedBox3d box = view_->surface_bounds();
  const double r = 0.05 * (box.isEmpty() ? 1.0 : box.diagonal().norm());
  int shown = 0;
  doc_.begin_gesture();
  const FrameTimes drag = timed_frames(frames, [&](int i) {
    SpaceTimeEdit e = e0;
    const double a = 2 * M_PI * (i + 1) / std::max(1, frames);
    e.move += r * Eigen::Vector3d(std::sin(a), 1 - std::cos(a), 0);
    doc_.set_space_time_edit(index, e);
    tick(0);
  }, [&](bool measured) { shown += measured && view_->showing_slice() && view_->display_vertex_count() > 0; });
  doc_.end_gesture();
  const FrameTimes still = posed_frames(frames, false);  // the edited slice, nothing changing
  doc_.undo();
  const FrameStages d = drag.mean_stages(), q = still.mean_stages();
  std::printf("drag-frames: %d frames (%d showed the edited slice), %s\n", int(drag.ms.size()), shown, drag.summary().c_str());
  std::printf("drag-frames: mean per stage: ui %.2f ms, deform %.2f ms, scene draw %.2f ms, imgui draw %.2f ms\n", d.ui,
              d.sync, d.scene, d.imgui);
  std::printf("drag-frames: the edited slice redrawn still: mean %.2f ms (deform %.2f ms, scene draw %.2f ms)\n",
              still.mean(), q.sync, q.scene);
  const FrameTimes posed = posed_frames(frames, true);
  const FrameStages p = posed.mean_stages();
  std::printf("drag-frames: posed mean per stage: ui %.2f ms, deform %.2f ms, scene draw %.2f ms, imgui draw %.2f ms\n",
              p.ui, p.sync, p.scene, p.imgui);
  std::printf("drag-frames: drag mean %.2f ms; posed mean %.2f ms; ratio %.2f\n", drag.mean(), posed.mean(),
              posed.mean() > 0 ? drag.mean() / posed.mean() : 0.0);
  std::fflush(stdout);
}

// As wait_for_manifold: frames while the panel's ARAP shape is on the worker (a frame when its
// progress text changes, at most progress_hz, the worker getting the CPU between them), each timed as
// the user would see it (drawn, swapped, finished): the UI frames must stay under 100 ms meanwhile.
void Editor::wait_for_shape_space() {
  const ShapeSpacePanel& p = *shape_space_;
  if (p.times.size() < 2) return;  // no shape space in use
  render_frame();  // the panel asks for the shape the last edits need (or collects it)
  if (!p.space || p.space->morph() != ShapeMorph::Arap) return;
  const double t0 = glfwGetTime();
  present_frame();
  JobFrameClock clock;
  clock.last = t0;
  int frames = 0, over_100 = 0;
  double sum_ms = 0, max_ms = 0;
  while (p.shape.waiting()) {
    if (!next_job_frame(clock)) continue;
    const double f0 = glfwGetTime();
    render_frame();  // also collects the shape and shows it
    present_frame();
    glfwPollEvents();
    glFinish();
    const double ms = 1000.0 * (glfwGetTime() - f0);
    ++frames, sum_ms += ms, max_ms = std::max(max_ms, ms), over_100 += ms > 100.0;
  }
  char shape[320];
  if (p.shape.final_at(p.weights))
    std::snprintf(shape, sizeof shape, "the ARAP shape at the cursor (%.2f s on the worker)", p.shape.synth_ms() / 1000.0);
  else
    std::snprintf(shape, sizeof shape, "no ARAP shape at the cursor (%s)", p.shape.error().substr(0, 200).c_str());
  std::printf("shape space: %s; waited %.2f s, %d frames drawn meanwhile, mean %.1f ms, max %.1f ms, %d over 100 ms\n",
              shape, glfwGetTime() - t0, frames, frames ? sum_ms / frames : 0.0, max_ms, over_100);
  std::fflush(stdout);
}

// "tool=rotate,weights=selected,wireframe=1,ortho=0,preset=iso,sweep=x,grid=0,frame=X:Y:Z:R": the state a user
// would click to, so a screenshot can show any tool. Unknown keys or values are errors.
void Editor::apply_ui_options(const std::string& spec) {
  size_t pos = 0;
  while (pos < spec.size()) {
    size_t end = spec.find(',', pos);
    if (end == std::string::npos) end = spec.size();
    const std::string item = spec.substr(pos, end - pos);
    pos = end + 1;
    const size_t eq = item.find('=');
    if (eq == std::string::npos) throw Error("--ui: expected key=value, got '" + item + "'");
    const std::string k = item.substr(0, eq), v = item.substr(eq + 1);
    auto bad = [&]() { return Error("--ui: bad value '" + v + "' for " + k); };
    if (shape_space_ui_option(k, v) || panel_ui_option(k, v)) {
    } else if (k == "tool") {
      if (v == "select") tool_ = Tool::Select;
      else if (v == "point") tool_ = Tool::PlacePoint;
      else if (v == "bone") tool_ = Tool::DrawBone;
      else if (v == "paint") tool_ = Tool::Paint;
      else if (v == "paint-weights") tool_ = Tool::Paint, paint_tool_.set_target(PaintTarget::Weights);
      else if (v == "move") tool_ = Tool::Pose, gizmo_rotate_ = false;
      else if (v == "rotate") tool_ = Tool::Pose, gizmo_rotate_ = true;
      else if (v == "pair") tool_ = Tool::Pair;
      else if (v == "sculpt") tool_ = Tool::Sculpt, sculpt_tool_.set_mode(SculptMode::Region);
      else if (v == "sculpt-transition") tool_ = Tool::Sculpt, sculpt_tool_.set_mode(SculptMode::Transition);
      else if (v == "spacetime") tool_ = Tool::SpaceTime;
      else throw bad();
    } else if (k == "weights") {
      if (v == "off") weight_view_ = WeightView::Off;
      else if (v == "selected") weight_view_ = WeightView::Selected;
      else if (v == "all") weight_view_ = WeightView::AllHandles;
      else if (v == "mask") weight_view_ = WeightView::Mask;
      else if (v == "difference") weight_view_ = WeightView::Difference;
      else throw bad();
    } else if (k == "wireframe" || k == "ortho" || k == "grid" || k == "handles") {
      if (v != "0" && v != "1") throw bad();
      bool& b = k == "wireframe" ? wireframe_ : k == "ortho" ? cam_.orthographic : k == "grid" ? show_grid_ : show_handles_;
      b = v == "1";
    } else if (k == "preset") {
      bool found = false;
      for (auto p : {view::ViewPreset::Front, view::ViewPreset::Back, view::ViewPreset::Left, view::ViewPreset::Right,
                     view::ViewPreset::Top, view::ViewPreset::Bottom, view::ViewPreset::Iso}) {
        std::string n = view::view_preset_name(p);
        std::transform(n.begin(), n.end(), n.begin(), ::tolower);
        if (n == v) view::set_view_preset(cam_, p), found = true;
      }
      if (!found) throw bad();
      frame_all();
    } else if (k == "sweep") {
      if (v != "t" && v != "x" && v != "y" && v != "z") throw bad();
      slice_axis_ = parse_slice_axis(v);
    } else if (k == "sweep_at") {  // the sweep's place, a fraction of the extent along its axis
      char* end = nullptr;
      const double f = std::strtod(v.c_str(), &end);
      if (end == v.c_str() || *end || !(f >= 0 && f <= 1)) throw bad();
      sweep_value_ = f;
    } else if (k == "frame") {
      if (v == "all") frame_all();
      else if (v == "selection") frame_selection_after_script_ = true;  // the script may select
      else if (double x = 0, y = 0, z = 0, r = 0; std::sscanf(v.c_str(), "%lf:%lf:%lf:%lf", &x, &y, &z, &r) == 4 && r > 0) {
        // frame=X:Y:Z:R: the sphere at X Y Z of radius R fills the viewport (a close-up for a screenshot).
        const Rect vp = panel_layout().viewport;
        cam_.width = vp.w, cam_.height = vp.h;
        view::frame_sphere(cam_, Eigen::Vector3d(x, y, z), r);
        sync_camera_to_doc();
      } else {
        throw bad();
      }
    } else if (k == "cursor") {
      double x = 0, y = 0;
      if (std::sscanf(v.c_str(), "%lfx%lf", &x, &y) != 2) throw bad();
      forced_cursor_ = Eigen::Vector2d(x, y);
    } else if (k == "vertex") {
      picked_vertex_ = std::atoi(v.c_str());
    } else {
      throw Error("--ui: unknown key '" + k + "' (tool, weights, wireframe, ortho, grid, handles, preset, sweep, sweep_at, vertex, cursor, frame, panels)");
    }
  }
}

}  // namespace dfm::editor
