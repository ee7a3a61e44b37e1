// The table's surface, rig, bind and mask commands (SCRIPT.md).
#include <cmath>
#include "core/scene/bind_document.h"
#include "core/scene/brush.h"
#include "core/scene/command_parts.h"
#include "core/scene/scene_import.h"
#include "core/util/error.h"

namespace dfm::command_detail {
namespace {

using Opened = ScriptHost::Opened;

void opened(const CommandContext& x, Opened what) {
  if (x.host.opened) x.host.opened(what);
}

void open(CommandContext& x, const CommandWords& w) {
  const bool imported = scene_importer_for(w[1]) != nullptr;  // rigged glTF, FBX, Collada (scene_import.h)
  const bool scene = imported || ends_with(w[1], ".json");
  if (imported) x.print("open: " + x.doc.import_scene(w[1]));
  else if (scene) x.doc.load_scene(w[1]);
  else x.doc.open_mesh(w[1]);  // a new document
  opened(x, scene ? Opened::Scene : Opened::NewMesh);
}

void pseudo_edge(CommandContext& x, const CommandWords& w) {
  const int a = handle_at(x.doc, w, 1), b = handle_at(x.doc, w, 2);
  for (int h : {a, b})
    if (handle_ref(x.doc.rig(), h).kind != HandleKind::Point)
      throw Error(handle_name(x.doc.rig(), h) + " (" + std::to_string(h) + ") is not a point handle");
  x.doc.add_pseudo_edge(a, b);
}

// One dab of the Paint tool's brush (brush.h): paint-mask sets VALUE, paint-dab adds or erases.
void paint(CommandContext& x, const CommandWords& w) {
  Brush brush{num(w, 4), num(w, 5), 0.0, BrushMode::Set};
  if (w[0] == "paint-mask") {
    if (brush.strength < 0 || brush.strength > 1) throw Error("mask values are in [0, 1], got " + w[5]);
    if (w.size() > 6) brush.falloff = num(w, 6);
  } else {
    brush.falloff = num(w, 6);
    if (w.size() > 7 && w[7] != "erase") throw Error("the last word is 'erase' or nothing, got " + w[7]);
    brush.mode = w.size() > 7 ? BrushMode::Erase : BrushMode::Add;
  }
  if (brush.radius <= 0) throw Error("radius must be > 0");
  const BrushDab dab = brush_dab(x.doc.surface().V, x.doc.mask(), Eigen::Vector3d(num(w, 1), num(w, 2), num(w, 3)), brush);
  if (dab.vertices.empty()) throw Error("no surface vertex within " + w[4] + " of the point");
  x.doc.paint_mask(dab.vertices, dab.values);
}

void bind_monotone(CommandContext& x, const CommandWords& w) {
  if (w[1] != "on" && w[1] != "off") throw Error("bind-monotone: expected on or off, got '" + w[1] + "'");
  BindSettings b = x.doc.bind_settings();
  b.monotone = w[1] == "on";
  x.doc.set_bind_settings(b);
}

void bind_additional(CommandContext& x, const CommandWords& w) {
  const double k = num(w, 1);
  if (k != std::floor(k) || k < 0 || k > kMaxAdditionalWeights)
    throw Error("bind-additional: K must be an integer in 0.." + std::to_string(kMaxAdditionalWeights) + ", got '" + w[1] + "'");
  BindSettings b = x.doc.bind_settings();
  b.additional_weights = static_cast<int>(k);
  x.doc.set_bind_settings(b);
}

}  // namespace

void add_rig_commands(std::vector<Command>& t) {
  Command* c = &add(t, "open", "open FILE", 1, 1, {file_arg()}, open);
  c->undoable = false;  // a new document: undo starts empty
  c->remember_file = true;
  c = &add(t, "load-motion", "load-motion FILE.bvh", 1, 1, {file_arg()},
           [](CommandContext& x, const CommandWords& w) { x.print("load-motion: " + x.doc.load_motion(w[1])); });
  c->remember_file = true;
  c = &add(t, "replace-surface", "replace-surface FILE", 1, 1, {file_arg()}, [](CommandContext& x, const CommandWords& w) {
    x.doc.replace_surface(w[1]);
    opened(x, Opened::Surface);
  });
  c->poll = needs_surface;
  c->remember_file = true;
  add(t, "add-point", "add-point X Y Z", 3, 3, {number_arg()}, [](CommandContext& x, const CommandWords& w) {
    x.doc.add_point({num(w, 1), num(w, 2), num(w, 3)});
  });
  c = &add(t, "add-bone", "add-bone X0 Y0 Z0 X1 Y1 Z1 [X2 Y2 Z2 ...]", 6, 3000, {number_arg()},
           [](CommandContext& x, const CommandWords& w) {
             std::vector<Eigen::Vector3d> joints;
             for (size_t i = 1; i + 2 < w.size(); i += 3) joints.push_back({num(w, i), num(w, i + 1), num(w, i + 2)});
             x.doc.add_bone_chain(joints);
           });
  c->check = [](const CommandWords& w, const std::string&) {
    if ((w.size() - 1) % 3 != 0)
      throw Error("add-bone needs joint positions in threes (x y z), got " + std::to_string(w.size() - 1) + " numbers");
  };
  // A chain hanging from joint J: J's bone to the first new joint, and on through the rest.
  c = &add(t, "add-bone-from", "add-bone-from JOINT X1 Y1 Z1 [X2 Y2 Z2 ...]", 4, 3001, {number_arg()},
           [](CommandContext& x, const CommandWords& w) {
             std::vector<Eigen::Vector3d> joints;
             for (size_t i = 2; i + 2 < w.size(); i += 3) joints.push_back({num(w, i), num(w, i + 1), num(w, i + 2)});
             const double j = num(w, 1);
             if (j < 0 || j != std::floor(j)) throw Error("JOINT must be a joint number, got " + w[1]);
             x.doc.add_bone_chain(joints, static_cast<int>(j));
           });
  c->check = [](const CommandWords& w, const std::string&) {
    if ((w.size() - 2) % 3 != 0)
      throw Error("add-bone-from needs joint positions in threes (x y z) after the joint, got " +
                  std::to_string(w.size() - 2) + " numbers");
  };
  c = &add(t, "load-skeleton", "load-skeleton FILE.tgf", 1, 1, {file_arg()},
           [](CommandContext& x, const CommandWords& w) { x.doc.load_skeleton(w[1]); });
  c->remember_file = true;
  c = &add(t, "load-cage", "load-cage FILE", 1, 1, {file_arg()},
           [](CommandContext& x, const CommandWords& w) { x.doc.load_cage(w[1]); });
  c->remember_file = true;
  add(t, "pseudo-edge", "pseudo-edge POINT_A POINT_B", 2, 2, {handle_arg()}, pseudo_edge);
  add(t, "delete-handles", "delete-handles HANDLE [HANDLE ...]", 1, 1000, {handle_arg()},
      [](CommandContext& x, const CommandWords& w) {
        std::vector<int> handles;
        for (size_t i = 1; i < w.size(); ++i) handles.push_back(handle_at(x.doc, w, static_cast<int>(i)));
        x.doc.delete_handles(handles);
      });
  // The name is the rest of the line (one space between words).
  add(t, "rename-handle", "rename-handle HANDLE NAME", 2, 1000, {handle_arg(), word_arg()},
      [](CommandContext& x, const CommandWords& w) {
        std::string name = w[2];
        for (size_t i = 3; i < w.size(); ++i) name += " " + w[i];
        x.doc.rename_handle(handle_at(x.doc, w, 1), name);
      });
  add(t, "paint-mask", "paint-mask X Y Z RADIUS VALUE [FALLOFF]", 5, 6, {number_arg()}, paint).poll = needs_surface;
  add(t, "paint-dab", "paint-dab X Y Z RADIUS STRENGTH FALLOFF [erase]", 6, 7,
      {number_arg(), number_arg(), number_arg(), number_arg(), number_arg(), number_arg(), word_arg()}, paint)
      .poll = needs_surface;
  c = &add(t, "bind", "bind", 0, 0, {}, [](CommandContext& x, const CommandWords&) {
    if (x.host.bind) x.host.bind(x.doc);
    else run_bind_blocking(x.doc);
  });
  c->poll = [](const Document& d) {
    if (const std::string why = needs_surface(d); !why.empty()) return why;
    return d.num_handles() > 0 ? std::string() : std::string("no handles (add a point, bones or a cage)");
  };
  add(t, "bind-monotone", "bind-monotone on|off", 1, 1, {word_arg()}, bind_monotone);
  add(t, "bind-additional", "bind-additional K", 1, 1, {number_arg()}, bind_additional);
}

}  // namespace dfm::command_detail
