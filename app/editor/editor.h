#pragma once
// The editor window: one Document (the single source of truth), the GPU state mirroring it, the
// camera, the loop, and the tools and panels (each its own unit: pose_tool.h, rig_drag.h, paint_tool.h,
// bone_tool.h, pair_tool.h, pose_panels.h, weight_tools_panel.h). Edits run the command table's lines
// (run_ui_command), as a script does; panels read the document.
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "app/editor/batch_runner.h"
#include "app/editor/bind_worker.h"
#include "app/editor/file_panel.h"
#include "app/editor/frame_pacing.h"
#include "app/editor/bone_tool.h"
#include "app/editor/pair_tool.h"
#include "app/editor/sculpt_tool.h"
#include "app/editor/space_time_tool.h"
#include "app/editor/paint_tool.h"
#include "app/editor/pose_panels.h"
#include "app/editor/pose_tool.h"
#include "app/editor/rig_drag.h"
#include "app/editor/scene_view.h"
#include "app/editor/timeline_ruler.h"
#include "app/editor/view_model.h"
#include "app/editor/weight_tools_panel.h"
#include "core/scene/command.h"
#include "core/scene/document.h"
#include "core/view/camera.h"
#include "render/gl_backend.h"
#include "render/gl_context.h"

struct GLFWwindow;

namespace dfm::editor {

struct EditorOptions {
  std::string file;        // scene or mesh to open ("" = default scene)
  std::string script;      // --script
  std::string screenshot;  // --screenshot (after the script)
  bool quit = false;       // --quit
  std::string ui;          // --ui key=value,...: initial tool / view state (screenshots, tests)
  int play_frames = 0;     // --play-frames N: play the timeline N frames, print frame times
  int drag_frames = 0;     // --drag-frames N: drag the last space-time edit N frames against posing
  int width = 1280, height = 800;
  std::string bind_screenshot;  // --bind-screenshot F.png: a PNG of the window while a script's bind runs
  int msaa = -1;           // --msaa N: multisample count (-1: 4, or 0 on a software renderer)
};

enum class Tool { Select, PlacePoint, DrawBone, Paint, Pose, Pair, Sculpt, SpaceTime };

struct ShapeSpacePanel;
class ItemFlow;

class Editor {
 public:
  explicit Editor(const EditorOptions& opts);
  ~Editor();
  // Runs the script / screenshot / interactive loop; returns the process exit code.
  int run();

  // Public for the script host and tests.
  void render_frame();                       // one full frame (scene + UI), no swap
  void present_frame();                      // swaps the frame render_frame drew; times it for the HUD
  void note_event() { ++events_; }           // GLFW callbacks: input or a window change (redraw)
  // Milliseconds of the last render_frame's stages when profiling (glFinish between stages).
  struct FrameStages {
    double ui = 0, sync = 0, scene = 0, imgui = 0;
  };
  void save_screenshot(const std::string& path);
  // A scene, mesh or tet mesh (a new document: asks first when the open one has unsaved changes),
  // a skeleton (added to the rig), or a cage (Alt+drop) by extension, as the table's command for it;
  // errors go to the popup.
  void open_any(const std::string& path);
  Document& document() { return doc_; }

 private:
  // editor_commands.cpp: the editor's side of the command table (core/scene/command.h).
  // The host every command runs with: screenshots, glTF export with its report, the UI's bind on the
  // worker, and show_opened after open and replace-surface.
  ScriptHost command_host();
  // A menu item, button, shortcut or the file panel: runs the line as a script would, remembers a
  // file it opened or saved, shows what the command printed (else the line) as the status and in
  // *printed; an error goes to the popup (false).
  bool run_ui_command(const CommandWords& words, std::string* printed = nullptr);
  void load_initial();  // the command line's file (or the default scene), by `open`
  void run_script_file();  // --script: every line checked, then run with the batch bind (batch_runner.h)
  void draw_open_prompt();  // "Discard unsaved changes?" before a new document replaces a dirty one
  // editor.cpp
  void init_imgui();
  // Every open of a scene or mesh, by the menu, a drop, the command line or a script, ends here (the
  // host's opened()): a new document gets a fresh document's view settings, then the view syncs and
  // frames it (a scene by its saved camera, a mesh from the three-quarter view).
  void show_opened(ScriptHost::Opened what);
  void fit_scene_radius();  // from the surface's bounds (pan/zoom speeds, gizmo size)
  void frame_all();
  void frame_selection();
  void sync_camera_to_doc();
  void tick(double dt);
  void status(const std::string& msg, bool error = false);
  void request_quit();
  void autosave_if_due();
  // The interactive loop's wait: draws on input, while playing, and at most 30 Hz while a job runs;
  // otherwise sleeps in glfwWaitEventsTimeout.
  void wait_for_frame();
  // The HUD's first line (fps, ms, counts, view), also printed by a script's `screenshot`.
  std::string hud_text() const;
  // What a running job shows (bind stage, percent, elapsed tenths; the transition build's text), ""
  // without one: a frame is due when it changes.
  std::string job_progress_signature() const;
  // A script waiting on a job: true when a frame is due (the job's display changed, at most
  // progress_hz, or the heartbeat), else sleeps a few milliseconds handling events.
  struct JobFrameClock {
    double last = -1e300;
    std::string shown;
  };
  bool next_job_frame(JobFrameClock& clock);
  void play_benchmark(int frames);
  void drag_benchmark(int frames);
  // Frame times of a batch benchmark (--play-frames, --drag-frames) and their stage sums.
  struct FrameTimes {
    std::vector<double> ms;  // one per measured frame
    FrameStages sum;
    double mean() const;
    FrameStages mean_stages() const;
    std::string summary() const;  // mean, median, p95, max
  };
  FrameTimes timed_frames(int frames, const std::function<void(int)>& before,
                          const std::function<void(bool)>& after = {});
  FrameTimes posed_frames(int frames, bool reskin);
  void print_mid_frame();
  void apply_ui_options(const std::string& spec);
  // editor_input.cpp
  void handle_shortcuts();
  void handle_viewport_input();
  void handle_camera_input();
  void tool_select(bool clicked, bool released);
  void tool_place_point(bool clicked);
  void tool_draw_bone(bool clicked);
  void tool_paint(bool down, bool clicked, bool released);
  void tool_pair(bool clicked);
  void tool_sculpt(bool down, bool clicked, bool released);
  void tool_space_time(bool clicked, bool released);
  void finish_bone_chain();
  void tool_pose(bool clicked, bool released);
  Eigen::Vector2d mouse_in_viewport() const;
  // editor_panels.cpp
  bool available(const char* command) const;  // the table command's poll allows it (menus, buttons)
  void draw_ui();
  void draw_menu_bar();
  void draw_left_panel();
  void draw_outliner();
  void draw_tools_panel();
  void draw_right_panel();
  void draw_view_section();
  void draw_bind_section();
  void draw_weights_section();
  void draw_weight_difference_note();
  void draw_transform_section();
  void draw_posing_section();  // pose_panels.cpp
  // --ui panels=weights:posing: the right panel's sections to show open (the others closed).
  bool panel_ui_option(const std::string& key, const std::string& value);
  // shape_space_panel.cpp: the Shape space panel (Alexa 2002, ch. 5) and its --ui options.
  void draw_shape_space_section();
  bool shape_space_ui_option(const std::string& key, const std::string& value);
  void update_shape_space();   // rebuilds the space when the bases' surfaces change
  void shape_space_pad(ShapeSpacePanel& p);
  // "synthesizing (ARAP) 1.2 s" while the panel waits for its worker's shape, else "" (a job's
  // progress: the loop draws when it changes).
  std::string shape_space_progress() const;
  // The cursor's shape when it is the space's own synthesis for these bases, morph and coordinates
  // (the ARAP one the worker made), for shape-space-key; else empty.
  Eigen::MatrixXd shape_space_ready(const std::vector<double>& times, ShapeMorph morph, const Eigen::VectorXd& x) const;
  // Draws frames until the panel's ARAP shape for the cursor has arrived (scripts, --screenshot), and
  // prints the frames' times; editor_batch.cpp.
  void wait_for_shape_space();
  void draw_weight_tools_section();  // weight_tools_panel.cpp (inside the Weights section)
  void draw_viewport_hud();
  void draw_quit_prompt();
  void draw_error_popup();
  // editor_timeline.cpp
  void draw_timeline();
  void draw_timeline_toolbar();
  // actions
  void start_bind();
  bool save_scene_as(const std::string& path);  // `save-scene PATH` from the UI; false: failed, reported
  void draw_inbetween_choice(ItemFlow& flow);  // the timeline's in-between combo (theme.h's ItemFlow)
  // Draws frames until the viewport's manifold has finished building (scripts, --screenshot).
  void wait_for_manifold();
  // File > Export glTF and `export-gltf`: returns the report as text (also shown in a popup).
  std::string export_gltf(const std::string& path, int influences);
  void draw_export_report();
  void select_handle(int handle, bool additive);

  EditorOptions opts_;
  gl::Context ctx_;
  GLFWwindow* window_ = nullptr;
  Document doc_;
  std::unique_ptr<gl::GlBackend> gpu_;  // the viewport's passes; outlives view_
  std::unique_ptr<SceneView> view_;
  view::Camera cam_;
  BindWorker bind_;
  FilePanel files_;

  // UI state
  Tool tool_ = Tool::Select;
  WeightView weight_view_ = WeightView::Off;
  bool place_inside_ = true;
  bool gizmo_rotate_ = false;
  bool wireframe_ = false;
  bool show_grid_ = true;
  bool show_handles_ = true;
  bool playing_ = false;
  bool loop_ = true;
  double play_speed_ = 1.0;
  SliceAxis slice_axis_ = SliceAxis::T;  // T: time slices; X, Y, Z: the sweep view along that axis
  double sweep_value_ = 0.5;  // fraction of the extent along the sweep axis
  int picked_vertex_ = -1;    // vertex whose weights are listed
  BoneTool bone_tool_;    // a bone chain in the making (bone_tool.h)
  Rect viewport_;
  bool viewport_hovered_ = false;
  double timeline_h_ = 118;  // the timeline's height (its toolbar wraps to more rows on narrow windows)
  std::uint64_t dynamics_revision_ = 0;  // the document's revision after the last tick (dynamics steps)
  double frame_rate_ = 24;   // the timeline shows time as frames at this rate (and seconds)
  int open_sections_ = -1;   // --ui panels: a bit per right-panel section to open at the next frame
  // The panels for the window's current size (view_model.h's layout_panels): draw_ui lays them out, and
  // framing before the first frame fits the scene into the viewport they leave.
  PanelLayout panel_layout() const;

  // gestures
  enum class Drag { None, Orbit, Pan } drag_ = Drag::None;  // the camera's drags
  Eigen::Vector2d drag_last_ = Eigen::Vector2d::Zero();
  RigDrag rig_drag_;    // the Select tool's drag of a rest-pose handle or joint (rig_drag.h)
  PoseTool pose_tool_;  // the gizmo and its drag (pose_tool.h)
  PaintTool paint_tool_;  // the brush, its settings and its stroke (paint_tool.h)
  PairTool pair_tool_;    // a picked pair in the making (pair_tool.h)
  SculptTool sculpt_tool_;  // the Sculpt tool's brush, handle drag and settings (sculpt_tool.h)
  SpaceTimeTool space_time_tool_;  // the space-time edit's settings and drag (space_time_tool.h)
  TimelineRuler timeline_ruler_;  // the timeline's ruler and its drags (timeline_ruler.h)
  PosePanels pose_panels_;  // the Transform and Posing sections (pose_panels.h)

  // timing and messages
  FrameTally bind_tally_;  // UI frames drawn while the last bind ran (each should stay < 100 ms)
  bool profile_stages_ = false;
  std::optional<Eigen::Vector2d> forced_cursor_;
  bool frame_selection_after_script_ = false;  // --ui frame=selection  // --ui cursor=XxY: the mouse held there (screenshots)  // render_frame: glFinish after each stage and time it (play-frames)
  FrameStages stages_;
  FrameStats frame_stats_;
  FramePacer pacer_;
  std::uint64_t events_ = 0, events_seen_ = 0;
  std::string job_progress_seen_;
  std::string status_;
  bool status_error_ = false;
  std::string error_popup_;
  std::string export_report_;  // shown in the "glTF export" popup until closed
  bool quit_prompt_ = false;
  std::string pending_open_;  // a file waiting on "Discard unsaved changes?"
  bool should_quit_ = false;
  std::chrono::steady_clock::time_point last_autosave_;
  std::uint64_t autosaved_revision_ = 0;
  std::vector<std::string> weight_rows_;  // the picked vertex's weights, formatted
  std::unique_ptr<ShapeSpacePanel> shape_space_;  // the Shape space panel's view state
  WeightToolsUi weight_tools_;  // the Weights panel's tools (weight_tools_panel.h)
};

}  // namespace dfm::editor
