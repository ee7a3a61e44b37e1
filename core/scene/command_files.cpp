// The table's commands that write files, the ones the host (the editor) runs, and quit (SCRIPT.md).
#include <cmath>
#include <string>

#include "core/anim/frame_sequence.h"
#include "core/mesh/io.h"
#include "core/scene/command_parts.h"
#include "core/scene/key_surfaces.h"
#include "core/scene/script.h"
#include "core/util/error.h"

namespace dfm::command_detail {
namespace {

void save_frames(CommandContext& x, const CommandWords& w) {
  const int count = w.size() > 2 ? static_cast<int>(num(w, 2)) : kDefaultFrameCount;  // an integer: checked
  if (x.doc.keys().size() < 2) throw Error("save-frames needs at least two keys");
  write_frame_sequence(document_manifold(x.doc), w[1], count);
}

ArgSpec frame_count_arg() {
  return {ArgKind::Number, [](const std::string& w, const std::string&) {
            double c;
            if (!parse_number(w, c) || c < 2 || c != std::floor(c) || c > 100000)
              throw Error("frame count '" + w + "' must be an integer >= 2");
          }};
}

ArgSpec gltf_file_arg() {
  return {ArgKind::File, [](const std::string& w, const std::string&) {
            if (!ends_with(w, ".glb") && !ends_with(w, ".gltf")) throw Error("export-gltf writes .glb or .gltf, got '" + w + "'");
          }};
}

ArgSpec influences_arg() {
  return {ArgKind::Number, [](const std::string& w, const std::string&) {
            if (w != "4" && w != "8") throw Error("influences per vertex must be 4 or 8, got '" + w + "'");
          }};
}

}  // namespace

void add_file_commands(std::vector<Command>& t) {
  Command* c = &add(t, "save-posed", "save-posed OUT.obj|ply|off|stl", 1, 1, {file_arg()},
                    [](CommandContext& x, const CommandWords& w) { write_surface(w[1], posed_surface(x.doc)); });
  c->undoable = false;
  c->poll = needs_a_frame;
  c = &add(t, "save-frames", "save-frames PREFIX [COUNT]", 1, 2, {file_arg(), frame_count_arg()}, save_frames);
  c->undoable = false;
  c->poll = needs_two_keys;
  c = &add(t, "save-scene", "save-scene FILE.scene.json", 1, 1, {file_arg()},
           [](CommandContext& x, const CommandWords& w) { x.doc.save_scene(w[1]); });
  c->undoable = false;
  c->remember_file = true;
  c = &add(t, "screenshot", "screenshot OUT.png", 1, 1, {file_arg()}, [](CommandContext& x, const CommandWords& w) {
    if (!x.host.screenshot) throw Error("screenshots need the editor (no renderer here)");
    x.host.screenshot(w[1]);
  });
  c->undoable = false;
  c = &add(t, "export-gltf", "export-gltf OUT.glb|OUT.gltf [4|8]", 1, 2, {gltf_file_arg(), influences_arg()},
           [](CommandContext& x, const CommandWords& w) {
             if (!x.host.export_gltf) throw Error("glTF export needs the editor (or `deform export`)");
             x.host.export_gltf(w[1], w.size() > 2 ? std::stoi(w[2]) : 4);
           });
  c->undoable = false;
  c->poll = needs_weights;
  c = &add(t, "quit", "quit", 0, 0, {}, [](CommandContext& x, const CommandWords&) { x.quit = true; });
  c->undoable = false;
}

}  // namespace dfm::command_detail
