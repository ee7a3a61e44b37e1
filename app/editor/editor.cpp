#include "app/editor/editor.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "app/editor/camera_sync.h"
#include "app/editor/shape_space_panel.h"
#include "app/editor/theme.h"
#include "core/mesh/io.h"
#include "core/scene/bind_document.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "render/screenshot.h"

namespace fs = std::filesystem;

namespace dfm::editor {
namespace {

constexpr double kAutosaveSeconds = 180.0;

// A three-quarter view from slightly above: shows depth better than a flat front view.
Eigen::Quaterniond default_orientation() {
  return Eigen::Quaterniond(Eigen::AngleAxisd(0.45, Eigen::Vector3d::UnitY())) *
         Eigen::Quaterniond(Eigen::AngleAxisd(-0.22, Eigen::Vector3d::UnitX()));
}

// 4x MSAA triples the frame time on llvmpipe (measured: 138 -> 38 ms a frame on the default scene),
// so a software renderer gets none unless --msaa asks; a GPU gets 4x. One throwaway context tells.
int auto_msaa() {
  std::string r;
  {
    gl::Context probe(gl::ContextOptions{64, 64, false, 0, "deform-editor probe"});
    r = probe.renderer();
  }
  for (const char* soft : {"llvmpipe", "softpipe", "SwiftShader", "Software Rasterizer"})
    if (r.find(soft) != std::string::npos) return 0;
  return 4;
}

void drop_callback(GLFWwindow* w, int count, const char** paths) {
  auto* ed = static_cast<Editor*>(glfwGetWindowUserPointer(w));
  ed->note_event();
  for (int i = 0; i < count; ++i) ed->open_any(paths[i]);
}

// Every input or window event asks for a redraw: the idle loop sleeps until one arrives.
void note(GLFWwindow* w) { static_cast<Editor*>(glfwGetWindowUserPointer(w))->note_event(); }

// Installed before ImGui's backend, which chains to them (its own callbacks call these after).
void install_event_callbacks(GLFWwindow* w) {
  glfwSetKeyCallback(w, [](GLFWwindow* win, int, int, int, int) { note(win); });
  glfwSetCharCallback(w, [](GLFWwindow* win, unsigned) { note(win); });
  glfwSetMouseButtonCallback(w, [](GLFWwindow* win, int, int, int) { note(win); });
  glfwSetScrollCallback(w, [](GLFWwindow* win, double, double) { note(win); });
  glfwSetCursorPosCallback(w, [](GLFWwindow* win, double, double) { note(win); });
  glfwSetCursorEnterCallback(w, [](GLFWwindow* win, int) { note(win); });
  glfwSetWindowFocusCallback(w, [](GLFWwindow* win, int) { note(win); });
  glfwSetWindowSizeCallback(w, [](GLFWwindow* win, int, int) { note(win); });
  glfwSetFramebufferSizeCallback(w, [](GLFWwindow* win, int, int) { note(win); });
  glfwSetWindowRefreshCallback(w, [](GLFWwindow* win) { note(win); });
  glfwSetWindowIconifyCallback(w, [](GLFWwindow* win, int) { note(win); });
  glfwSetWindowCloseCallback(w, [](GLFWwindow* win) { note(win); });
}

}  // namespace

Editor::Editor(const EditorOptions& opts)
    : opts_(opts),
      ctx_(gl::ContextOptions{opts.width, opts.height, true, opts.msaa >= 0 ? opts.msaa : auto_msaa(), "deform-editor"}) {
  window_ = ctx_.window();
  glfwSetWindowUserPointer(window_, this);
  glfwSetDropCallback(window_, drop_callback);
  install_event_callbacks(window_);
  glfwSwapInterval(opts.quit ? 0 : 1);
  init_imgui();
  gpu_ = std::make_unique<gl::GlBackend>();
  view_ = std::make_unique<SceneView>(*gpu_);
  shape_space_ = std::make_unique<ShapeSpacePanel>();
  last_autosave_ = std::chrono::steady_clock::now();
  cam_.orientation = default_orientation();  // an empty document shows its grid from above, not edge-on
}

Editor::~Editor() {
  view_.reset();
  gpu_.reset();
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

void Editor::init_imgui() {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // layout is fixed; nothing to litter the working folder with
  float xscale = 1, yscale = 1;
  glfwGetWindowContentScale(window_, &xscale, &yscale);
  apply_theme(std::max(1.0f, xscale));
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
}

void Editor::status(const std::string& msg, bool error) {
  status_ = msg;
  status_error_ = error;
  if (error) std::fprintf(stderr, "deform-editor: %s\n", msg.c_str());
}

void Editor::show_opened(ScriptHost::Opened what) {
  if (what != ScriptHost::Opened::Surface) {
    // A fresh document's view: nothing of the last one's tools, selection helpers or playback.
    tool_ = Tool::Select;
    weight_view_ = WeightView::Off;
    wireframe_ = false;
    show_grid_ = true;
    show_handles_ = true;
    playing_ = false;
    slice_axis_ = SliceAxis::T;
    picked_vertex_ = -1;
    weight_rows_.clear();
    bone_tool_.cancel();
    pair_tool_.cancel();
    sculpt_tool_.cancel(doc_);
    paint_tool_.new_document();
    weight_tools_ = WeightToolsUi{};
  }
  view_->sync(doc_, {});
  if (what == ScriptHost::Opened::Scene) {
    view::Camera c = cam_;
    from_document_camera(doc_.camera(), c);
    cam_ = c;
    fit_scene_radius();
  } else {
    if (what == ScriptHost::Opened::NewMesh) cam_.orientation = default_orientation(), cam_.orthographic = false;
    frame_all();
  }
}

void Editor::fit_scene_radius() {
  cam_.scene_radius = std::max(1e-6, 0.5 * view_->surface_bounds().diagonal().norm());
}

void Editor::frame_all() {
  const Eigen::AlignedBox3d b = view_->framing_bounds();  // the surface and every handle
  if (b.isEmpty()) return;
  fit_scene_radius();
  const Rect v = panel_layout().viewport;  // the free viewport, also before the first frame
  cam_.width = v.w, cam_.height = v.h;
  view::frame_box(cam_, b.min(), b.max());
  sync_camera_to_doc();
}

void Editor::frame_selection() {
  const auto& sel = doc_.selection().handles;
  const Eigen::MatrixXd& P = view_->handle_positions();
  if (sel.empty() || P.rows() == 0) return frame_all();
  Eigen::AlignedBox3d b;
  for (int h : sel)
    if (h >= 0 && h < P.rows()) b.extend(Eigen::Vector3d(P.row(h)));
  if (b.isEmpty()) return frame_all();
  const double r = std::max(0.5 * b.diagonal().norm(), 0.12 * cam_.scene_radius);
  const Rect v = panel_layout().viewport;
  cam_.width = v.w, cam_.height = v.h;
  view::frame_sphere(cam_, b.center(), r);
  sync_camera_to_doc();
}

void Editor::sync_camera_to_doc() { doc_.set_camera(to_document_camera(cam_)); }

void Editor::select_handle(int handle, bool additive) {
  Selection s = doc_.selection();
  if (!additive) s.handles.clear();
  auto it = std::find(s.handles.begin(), s.handles.end(), handle);
  if (it != s.handles.end()) {
    if (additive) s.handles.erase(it);
  } else if (handle >= 0) {
    s.handles.insert(s.handles.begin(), handle);  // first = active
  }
  doc_.set_selection(s);
}

void Editor::tick(double dt) {
  // Collect a finished bind (one undo step), show what went wrong otherwise.
  if (auto r = bind_.take_result()) {
    if (r->ok) {
      try {
        apply_bind_result(doc_, *r->result);
        char msg[96];
        std::snprintf(msg, sizeof msg, "bound %d handles in %.2f s", doc_.num_handles(), r->result->report.total_seconds);
        status(msg);
        doc_.autosave();
        last_autosave_ = std::chrono::steady_clock::now();
      } catch (const std::exception& e) {
        error_popup_ = e.what();
      }
    } else if (r->cancelled) {
      status("bind cancelled");
    } else {
      error_popup_ = "Bind failed:\n" + r->error;
      status(r->error, true);
    }
  }
  // A live dynamics drag: one time step per drawn frame, unless this frame's drag already took it.
  if (doc_.dynamics_live() && doc_.revision() == dynamics_revision_) {
    try {
      doc_.step_dynamics();
    } catch (const std::exception& e) {
      status(std::string("dynamics: ") + e.what(), true);
    }
  }
  dynamics_revision_ = doc_.revision();
  if (playing_ && doc_.keys().size() >= 2) {
    const double t0 = doc_.keys().front().time, t1 = doc_.keys().back().time;
    double t = doc_.time() + dt * play_speed_;
    if (t > t1) t = loop_ ? t0 + std::fmod(t - t0, std::max(1e-9, t1 - t0)) : t1;
    if (!loop_ && t >= t1) playing_ = false;
    doc_.set_time(t);
  }
  autosave_if_due();
}

void Editor::autosave_if_due() {
  const auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - last_autosave_).count() < kAutosaveSeconds) return;
  last_autosave_ = now;
  if (!doc_.dirty() || doc_.revision() == autosaved_revision_) return;
  try {
    const std::string f = doc_.autosave();
    autosaved_revision_ = doc_.revision();
    status("autosaved to " + f);
  } catch (const std::exception& e) {
    status(std::string("autosave failed: ") + e.what(), true);
  }
}

void Editor::request_quit() {
  if (doc_.dirty()) {
    quit_prompt_ = true;
    glfwSetWindowShouldClose(window_, GLFW_FALSE);
  } else {
    should_quit_ = true;
  }
}

void Editor::render_frame() {
  frame_stats_.begin(glfwGetTime());
  int fb_w = 0, fb_h = 0, win_w = 0, win_h = 0;
  glfwGetFramebufferSize(window_, &fb_w, &fb_h);
  glfwGetWindowSize(window_, &win_w, &win_h);
  using clock = std::chrono::steady_clock;
  auto stage_end = [&](clock::time_point& t, double& out) {
    if (!profile_stages_) return;
    glFinish();
    const clock::time_point now = clock::now();
    out = std::chrono::duration<double, std::milli>(now - t).count();
    t = now;
  };
  clock::time_point t = clock::now();
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  if (forced_cursor_) ImGui::GetIO().MousePos = ImVec2(float(forced_cursor_->x()), float(forced_cursor_->y()));
  ImGui::NewFrame();
  draw_ui();  // lays out panels, sets viewport_
  draw_open_prompt();
  handle_shortcuts();
  handle_viewport_input();
  stage_end(t, stages_.ui);

  ViewSettings vs;
  vs.wireframe = wireframe_;
  vs.grid = show_grid_;
  vs.handles = show_handles_ && slice_axis_ == SliceAxis::T;  // a sweep slice is not in pose space: handles would mislead
  vs.weight_view = weight_view_;
  vs.slice_axis = slice_axis_;
  vs.sweep_value = sweep_value_;
  vs.sculpt_colors = tool_ == Tool::Sculpt;
  view_->sync(doc_, vs);
  stage_end(t, stages_.sync);
  ImGui::Render();

  // 3D viewport: the central rectangle left by the panels (window coords -> framebuffer pixels).
  const double sx = win_w > 0 ? double(fb_w) / win_w : 1.0, sy = win_h > 0 ? double(fb_h) / win_h : 1.0;
  glViewport(0, 0, fb_w, fb_h);
  glDisable(GL_SCISSOR_TEST);
  glClearColor(0.085f, 0.09f, 0.10f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  const int vx = int(viewport_.x * sx), vw = std::max(1, int(viewport_.w * sx));
  const int vh = std::max(1, int(viewport_.h * sy)), vy = fb_h - int(viewport_.y * sy) - vh;
  glViewport(vx, vy, vw, vh);
  glEnable(GL_SCISSOR_TEST);
  glScissor(vx, vy, vw, vh);
  // Vertical gradient background: draw by clearing two halves would band; a subtle flat tone reads well.
  glClearColor(0.145f, 0.15f, 0.165f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
  cam_.width = viewport_.w;
  cam_.height = viewport_.h;
  glEnable(GL_MULTISAMPLE);
  view_->draw(doc_, cam_, vs);
  stage_end(t, stages_.scene);

  glViewport(0, 0, fb_w, fb_h);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  stage_end(t, stages_.imgui);
}

void Editor::present_frame() {
  glfwSwapBuffers(window_);
  const double now = glfwGetTime();
  frame_stats_.end(now);
  pacer_.drew(frame_stats_.last_start());
}

std::string Editor::job_progress_signature() const {
  if (bind_.running()) {
    const BindProgress p = bind_.progress();
    return p.stage + " " + std::to_string(static_cast<int>(100.0 * p.fraction)) + "% " +
           std::to_string(static_cast<long>(10.0 * bind_.elapsed_seconds())) + (bind_.cancel_requested() ? " cancel" : "");
  }
  return view_->manifold_building() ? view_->manifold_progress() : shape_space_progress();
}

bool Editor::next_job_frame(JobFrameClock& c) {
  const double now = glfwGetTime();
  const PacingOptions& o = pacer_.options();
  const std::string shown = job_progress_signature();
  if ((shown != c.shown || now - c.last >= o.job_heartbeat_s) && now - c.last >= 1.0 / o.progress_hz) {
    c.shown = shown;
    c.last = now;
    return true;
  }
  glfwWaitEventsTimeout(0.005);
  return false;
}

void Editor::wait_for_frame() {
  for (;;) {
    LoopActivity a;
    a.input = events_ != events_seen_;
    events_seen_ = events_;
    a.playing = (playing_ && doc_.keys().size() >= 2) || doc_.dynamics_live();  // a settling drag draws every frame
    a.job_running = bind_.running() || view_->manifold_building() || !shape_space_progress().empty();
    const std::string progress = job_progress_signature();
    a.job_progress = progress != job_progress_seen_;
    job_progress_seen_ = progress;
    const double wait = pacer_.next(a, glfwGetTime());
    if (wait <= 0) return;
    if (!a.job_running) frame_stats_.pause();  // idle: the next frame does not follow on (a job's pacing does)
    glfwWaitEventsTimeout(wait);
    if (glfwWindowShouldClose(window_)) return;
    const std::string before = status_;
    autosave_if_due();  // timers run while idle too; a new status line is worth a frame
    if (status_ != before) ++events_;
  }
}

void Editor::save_screenshot(const std::string& path) {
  // Two frames first: ImGui sizes auto-fitting windows on the frame after they appear.
  for (int i = 0; i < 2; ++i) {
    render_frame();
    present_frame();
    glfwPollEvents();
  }
  render_frame();
  glFinish();
  int fb_w = 0, fb_h = 0;
  glfwGetFramebufferSize(window_, &fb_w, &fb_h);
  glReadBuffer(GL_BACK);
  gl::write_png(path, gl::read_framebuffer(fb_w, fb_h));
  present_frame();
  status("screenshot " + path);
}

void Editor::wait_for_manifold() {
  render_frame();  // syncs the view: starts a build the last edits need
  if (!view_->manifold_building()) return;
  const double t0 = glfwGetTime();
  present_frame();
  JobFrameClock clock;
  clock.last = glfwGetTime();
  while (view_->manifold_building()) {  // frames as its progress changes (at most progress_hz): the worker needs the CPU
    if (!next_job_frame(clock)) continue;
    render_frame();  // also collects the finished build
    present_frame();
    glfwPollEvents();
  }
  std::printf("animation manifold (transition) built on the worker in %.2f s%s%s\n", glfwGetTime() - t0,
              view_->last_error().empty() ? "" : ": ", view_->last_error().c_str());
  std::fflush(stdout);
}

int Editor::run() {
  load_initial();
  if (!opts_.ui.empty()) apply_ui_options(opts_.ui);
  if (cam_.scene_radius <= 0 || view_->surface_bounds().isEmpty()) cam_.scene_radius = 1.0;
  if (!opts_.script.empty()) run_script_file();
  if (frame_selection_after_script_) frame_selection();
  if (opts_.play_frames > 0) play_benchmark(opts_.play_frames);
  if (opts_.drag_frames > 0) drag_benchmark(opts_.drag_frames);
  if (!opts_.screenshot.empty()) wait_for_manifold(), wait_for_shape_space(), save_screenshot(opts_.screenshot);
  if (opts_.quit || should_quit_) return 0;

  // Idle: sleeps until an event (glfwWaitEventsTimeout); input, playback and a running job's
  // progress (at most progress_hz) draw frames (frame_pacing.h).
  double last = glfwGetTime();
  bool was_playing = false;
  while (!should_quit_) {
    glfwPollEvents();
    wait_for_frame();
    if (glfwWindowShouldClose(window_)) request_quit();
    const double now = glfwGetTime();
    // Playback advances by the time between its frames, not by the idle time before it started.
    const double dt = was_playing ? now - last : 0.0;
    last = now;
    const bool binding = bind_.running();
    tick(dt);
    was_playing = playing_;
    render_frame();
    present_frame();
    if (binding) bind_tally_.add(frame_stats_.last_ms());
  }
  return 0;
}

}  // namespace dfm::editor
