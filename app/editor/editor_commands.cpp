// The editor's side of the command table (core/scene/command.h): the host every command runs with
// (screenshots, glTF export with its report, the bind on the worker, showing what was opened), the
// UI's way to run a command line (menus, buttons, the file panel, a drop), and the script runner's.
#include <imgui.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "app/editor/batch_runner.h"
#include "app/editor/camera_sync.h"
#include "app/editor/editor.h"
#include "core/export/export_document.h"
#include "core/mesh/io.h"
#include "core/scene/bind_document.h"
#include "core/scene/script.h"
#include "core/scene/scene_import.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"

namespace fs = std::filesystem;

namespace dfm::editor {
namespace {

// The command that opening a file runs: a skeleton adds to the rig, a surface dropped with Alt onto a
// document that has one adds a cage, anything else opens (a new document).
CommandWords open_command(const std::string& path, bool alt, bool has_surface, bool has_bones) {
  const std::string ext = file_extension(path);
  if (ext == "tgf") return {"load-skeleton", path};
  // BVH: motion onto the rig by bone name; with no bones to drive, opened alone (its skeleton and keys).
  if (has_bones && motion_importer_for(path)) return {"load-motion", path};
  if (alt && has_surface && (ext == "obj" || ext == "off" || ext == "ply" || ext == "stl")) return {"load-cage", path};
  return {"open", path};
}

// The default scene ships in the source tree's assets/; look beside and above the executable so the
// editor runs from any working directory (build tree or install).
std::string find_default_scene() {
  if (const char* env = std::getenv("DFM_ASSETS_DIR")) {
    const fs::path p = fs::path(env) / "default.scene.json";
    if (fs::exists(p)) return p.string();
  }
  std::error_code ec;
  fs::path dir = fs::read_symlink("/proc/self/exe", ec).parent_path();
  for (int up = 0; !ec && up < 5 && !dir.empty(); ++up) {
    for (const char* rel : {"assets/default.scene.json", "share/deform/assets/default.scene.json"}) {
      const fs::path p = dir / rel;
      if (fs::exists(p)) return p.string();
    }
    if (dir == dir.parent_path()) break;
    dir = dir.parent_path();
  }
  return "";
}

std::string joined(const CommandWords& words) {
  std::string s;
  for (const std::string& w : words) s += (s.empty() ? "" : " ") + w;
  return s;
}

}  // namespace

ScriptHost Editor::command_host() {
  ScriptHost host;
  host.screenshot = [this](const std::string& png) {
    frame_stats_.pause();  // the commands ran since the last frame
    wait_for_manifold();  // a picture shows the animation that was keyed, not the build in progress
    wait_for_shape_space();  // ...and the Shape space panel's ARAP shape, not its linear stand-in
    save_screenshot(png);
    std::printf("screenshot: %s (HUD: %s)\n", png.c_str(), hud_text().c_str());
    std::fflush(stdout);
  };
  host.export_gltf = [this](const std::string& path, int influences) {
    std::printf("export-gltf: %s\n", export_gltf(path, influences).c_str());
    std::fflush(stdout);
  };
  host.opened = [this](ScriptHost::Opened what) { show_opened(what); };
  host.bind = [this](Document&) { start_bind(); };  // the UI's bind: the worker, collected by tick()
  host.synthesized_shape = [this](const std::vector<double>& times, ShapeMorph morph, const Eigen::VectorXd& x) {
    return shape_space_ready(times, morph, x);
  };
  return host;
}

bool Editor::run_ui_command(const CommandWords& words, std::string* printed) {
  try {
    sync_camera_to_doc();  // a saved scene keeps the view as it is now
    ScriptHost host = command_host();
    std::string out;
    host.print = [&](const std::string& line) {
      std::printf("%s\n", line.c_str());
      out += (out.empty() ? "" : "\n") + line;
    };
    run_command(doc_, words, host);
    const Command* c = find_command(words[0]);
    if (c && c->remember_file && words.size() > 1) files_.add_recent(words[1]);
    if (printed) *printed = out;
    status(out.empty() ? joined(words) : out);  // what the command said, else what a script would say
    return true;
  } catch (const std::exception& e) {
    error_popup_ = e.what();
    status(e.what(), true);
    return false;
  }
}

bool Editor::save_scene_as(const std::string& path) { return run_ui_command({"save-scene", path}); }

void Editor::open_any(const std::string& path) {
  if (const std::string why = unopenable_reason(path); !why.empty()) {  // e.g. a .glb
    error_popup_ = why;
    status(why, true);
    return;
  }
  const bool alt = ImGui::GetCurrentContext() && ImGui::GetIO().KeyAlt;
  const CommandWords words = open_command(path, alt, doc_.surface().num_vertices() > 0, doc_.rig().skeleton.num_bones() > 0);
  if (words[0] == "open" && doc_.dirty() && pending_open_ != path) {
    pending_open_ = path;  // draw_open_prompt asks, then calls open_any again
    return;
  }
  pending_open_.clear();
  run_ui_command(words);
}

void Editor::draw_open_prompt() {
  if (pending_open_.empty()) return;
  const char* title = "Discard unsaved changes?";
  if (!ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
  ImGui::SetNextWindowPos(ImGui::GetMainViewport()->GetCenter(), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  if (ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::Text("%s has unsaved changes.", fs::path(doc_.title()).filename().string().c_str());
    ImGui::Text("Opening %s starts a new document.", fs::path(pending_open_).filename().string().c_str());
    ImGui::TextDisabled("(File > Replace surface... keeps the rig on a new mesh.)");
    if (ImGui::Button("Discard and open")) {
      const std::string p = pending_open_;
      ImGui::CloseCurrentPopup();
      open_any(p);  // pending_open_ == p: opens without asking again
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) pending_open_.clear(), ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
}

void Editor::load_initial() {
  if (!opts_.file.empty()) {
    // A bad file on the command line is fatal for batch use (--quit), a message otherwise.
    if (!opts_.quit) return open_any(opts_.file);
    if (const std::string why = unopenable_reason(opts_.file); !why.empty()) throw Error(why);
    return run_command(doc_, open_command(opts_.file, false, false, false), command_host());
  }
  const std::string def = find_default_scene();
  if (def.empty()) {
    status("no default scene found (assets/default.scene.json); open a mesh with File > Open");
    return;
  }
  run_command(doc_, {"open", def}, command_host());
  // The default scene is a template: saving it should ask for a new name, not overwrite the asset.
  status("default scene: " + def);
}

void Editor::start_bind() {
  try {
    if (!bind_.start(make_document_bind_job(doc_))) status("a bind is already running");
    else bind_tally_ = FrameTally{};
  } catch (const std::exception& e) {
    error_popup_ = e.what();
  }
}

std::string Editor::export_gltf(const std::string& path, int influences) {
  GltfExportOptions o;
  o.influences = influences;
  o.refit = true;
  o.residual_morph_tolerance = 1e-4;  // as `deform export --residual-morphs`: keys replay exactly
  const GltfExportReport r = export_document_gltf(doc_, path, o);
  char buf[512];
  const double rel = r.bbox_diagonal > 0 ? r.max_prune_error / r.bbox_diagonal : 0.0;
  std::snprintf(buf, sizeof buf,
                "%s\n%d vertices, %d triangles, %d joints, %d influences, %d keys\n"
                "pruning error: %.3g (%.3g%% of the bbox diagonal) at %s\n"
                "%d vertices refit, %d residual morph targets, max shear %.2g",
                path.c_str(), r.vertices, r.triangles, r.joints, r.influences, r.keys, r.max_prune_error, 100.0 * rel,
                r.max_prune_error_key < 0 ? "the current pose" : ("key " + std::to_string(r.max_prune_error_key)).c_str(),
                r.refit_vertices, r.residual_targets, r.max_shear);
  std::string text = buf;
  for (const std::string& n : r.notes) text += "\nnote: " + n;
  export_report_ = text;
  status("exported " + path);
  return text;
}

// The script: every line checked first (read_script), then each runs with the editor's host: a bind
// on the worker with frames drawn meanwhile (batch_runner.h), a frame after each line.
void Editor::run_script_file() {
  const std::vector<ScriptLine> lines = read_script(opts_.script);
  ScriptHost host = command_host();
  host.bind = [this](Document& d) {
    frame_stats_.pause();
    BatchFrames frames;
    frames.draw = [this] {
      render_frame();
      present_frame();
      glfwPollEvents();
      glFinish();
    };
    JobFrameClock clock;
    frames.job_frame_due = [this, &clock] { return next_job_frame(clock); };
    frames.seconds = [] { return glfwGetTime(); };
    frames.after_frame = [this] {
      // Once the progress bar is past meshing (the docs' picture of a bind in progress).
      if (!opts_.bind_screenshot.empty() && bind_.progress().fraction > 0.35) {
        save_screenshot(opts_.bind_screenshot);
        opts_.bind_screenshot.clear();
      }
    };
    bind_with_frames(bind_, d, frames, bind_tally_);
  };
  host.after_command = [this](const ScriptLine&) {
    frame_stats_.pause();  // the command ran since the last frame
    render_frame();
    present_frame();
    glfwPollEvents();
  };
  if (run_script(doc_, lines, opts_.script, host).quit) should_quit_ = true;
}

}  // namespace dfm::editor
