#include "core/scene/script.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include "core/anim/frame_sequence.h"
#include "core/anim/inbetween_method.h"
#include "core/anim/manifold.h"
#include "core/anim/manifold_frame.h"
#include "core/pose/fast_rig.h"
#include "core/scene/bind_document.h"
#include "core/scene/brush.h"
#include "core/scene/key_surfaces.h"
#include "core/scene/script_weights.h"
#include "core/scene/shape_space_keys.h"
#include "core/mesh/io.h"
#include "core/skin/skin.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"

namespace dfm {

namespace {

// Argument shapes: a fixed count, or a range; `numbers` = how many leading arguments are numbers
// (-1: all of them).
struct Spec {
  int min_args, max_args;
  int numbers;
  const char* usage;
};

const std::map<std::string, Spec>& specs() {
  static const std::map<std::string, Spec> s = {
      {"open", {1, 1, 0, "open FILE"}},
      {"replace-surface", {1, 1, 0, "replace-surface FILE"}},
      {"add-point", {3, 3, -1, "add-point X Y Z"}},
      {"add-bone", {6, 3000, -1, "add-bone X0 Y0 Z0 X1 Y1 Z1 [X2 Y2 Z2 ...]"}},
      {"load-skeleton", {1, 1, 0, "load-skeleton FILE.tgf"}},
      {"load-cage", {1, 1, 0, "load-cage FILE"}},
      {"pseudo-edge", {2, 2, 0, "pseudo-edge POINT_A POINT_B"}},
      {"bind", {0, 0, 0, "bind"}},
      {"select", {1, 1000, 0, "select HANDLE [HANDLE ...]"}},
      {"translate", {3, 3, -1, "translate DX DY DZ"}},
      {"rotate", {4, 4, -1, "rotate DEGREES AX AY AZ"}},
      {"drag", {4, 4, 0, "drag HANDLE DX DY DZ"}},
      {"handle-state", {2, 2, 0, "handle-state HANDLE pinned|position|free"}},
      {"fast", {1, 2, 0, "fast on|off [ITERATIONS]"}},
      {"bind-monotone", {1, 1, 0, "bind-monotone on|off"}},
      {"ik-chain", {1, 1, 0, "ik-chain BONE_HANDLE"}},
      {"set-method", {1, 1, 0, "set-method lbs|dqs|stbs"}},
      {"set-key", {0, 1, -1, "set-key [TIME]"}},
      {"key-mesh", {1, 2, 0, "key-mesh FILE [TIME]"}},
      {"shape-space-key", {5, 2001, 0, "shape-space-key linear|arap T0 T1 ... W0 W1 ... [TIME]"}},
      {"delete-key", {0, 1, -1, "delete-key [TIME]"}},
      {"set-inbetween", {2, 2, 1, "set-inbetween TIME handles|arap|linear"}},
      {"set-time", {1, 1, -1, "set-time T"}},
      {"reset-pose", {0, 0, 0, "reset-pose"}},
      {"undo", {0, 0, 0, "undo"}},
      {"redo", {0, 0, 0, "redo"}},
      {"save-posed", {1, 1, 0, "save-posed OUT.obj|ply|off|stl"}},
      {"save-frames", {1, 2, 0, "save-frames PREFIX [COUNT]"}},
      {"save-scene", {1, 1, 0, "save-scene FILE.scene.json"}},
      {"screenshot", {1, 1, 0, "screenshot OUT.png"}},
      {"paint-mask", {5, 6, -1, "paint-mask X Y Z RADIUS VALUE [FALLOFF]"}},
      {"paint-dab", {6, 7, 6, "paint-dab X Y Z RADIUS STRENGTH FALLOFF [erase]"}},
      {"export-gltf", {1, 2, 0, "export-gltf OUT.glb|OUT.gltf [4|8]"}},
      {"weights-limit", {1, 2, -1, "weights-limit K [RADIUS]"}},
      {"weights-normalize", {0, 1000, 0, "weights-normalize [LOCKED_HANDLE ...]"}},
      {"weights-smooth", {0, 1000, 0, "weights-smooth [N [FACTOR [uniform|cotan [LOCKED_HANDLE ...]]]]"}},
      {"weights-mirror", {1, 4, 0, "weights-mirror x|y|z [OFFSET [+|-|flip [TOLERANCE]]]"}},
      {"weights-report", {0, 1, -1, "weights-report [THRESHOLD]"}},
      {"quit", {0, 0, 0, "quit"}},
  };
  return s;
}

bool parse_number(const std::string& w, double& out) {
  const char* b = w.c_str();
  char* e = nullptr;
  out = std::strtod(b, &e);
  return e != b && *e == '\0' && std::isfinite(out);
}

double num(const ScriptLine& l, int i) {
  double x = 0;
  parse_number(l.words[i], x);  // checked by parse_script
  return x;
}

// Words that name a handle (SCRIPT.md): a number or a name. Parse time checks numbers only (a name
// needs the rig the script has built by then); handle_arg resolves at run time (find_handle).
const std::map<std::string, std::vector<int>>& handle_words() {
  static const std::map<std::string, std::vector<int>> w = {
      {"select", {-1}}, {"drag", {1}}, {"handle-state", {1}}, {"ik-chain", {1}}, {"pseudo-edge", {1, 2}}};
  return w;
}

int handle_arg(const Document& doc, const ScriptLine& l, int i) { return find_handle(doc.rig(), l.words[i]); }

int integer_arg(const ScriptLine& l, int i) {
  const double x = num(l, i);
  if (x != std::floor(x) || std::abs(x) > 1e9) throw Error("'" + l.words[i] + "' is not an integer");
  return static_cast<int>(x);
}

bool ends_with(const std::string& s, const std::string& suf) {
  return s.size() >= suf.size() && s.compare(s.size() - suf.size(), suf.size(), suf) == 0;
}

std::vector<int> selected_or_fail(const Document& doc) {
  if (doc.selection().handles.empty()) throw Error("no handle selected (use: select HANDLE)");
  return doc.selection().handles;
}

TriMesh skinned(const Document& doc, const SkinBinding& binding, const Pose& pose,
                const std::vector<StbsHandle>& stbs) {
  TriMesh out;
  SkinResult r = skin(doc.method(), binding, pose, stbs);
  out.V = std::move(r.V);
  out.F = doc.surface().F;
  out.N = std::move(r.N);
  return out;
}

SkinBinding binding_of(const Document& doc) {
  if (!doc.has_weights()) throw Error("the scene has no weights: " + doc.weights_note() + " (run: bind)");
  return make_skin_binding(doc.surface().V, vertex_normals(doc.surface().V, doc.surface().F), doc.weights(),
                           doc.rig(), doc.bind_settings().max_influences);
}

// The frame without an animation (fewer than two keys): the one key (its mesh, or its pose skinned),
// else the current pose skinned with the current method.
TriMesh still_frame(const Document& doc) {
  if (doc.keys().size() == 1 && doc.keys()[0].is_mesh()) return doc.keys()[0].mesh;
  const SkinBinding binding = binding_of(doc);
  if (doc.keys().size() == 1) return skinned(doc, binding, doc.key_poses()[0], {});
  return skinned(doc, binding, doc.pose(), stbs_handles(doc.rig(), doc.pose_params().bone_twist_stretch));
}

}  // namespace

std::vector<ScriptLine> parse_script(const std::string& text, const std::string& name) {
  std::vector<ScriptLine> out;
  std::istringstream in(text);
  std::string raw;
  int line = 0;
  while (std::getline(in, raw)) {
    ++line;
    if (!raw.empty() && raw.back() == '\r') raw.pop_back();
    const size_t hash = raw.find('#');
    if (hash != std::string::npos) raw.erase(hash);
    ScriptLine l;
    l.line = line;
    std::istringstream ws(raw);
    for (std::string w; ws >> w;) l.words.push_back(w);
    if (l.words.empty()) continue;
    const auto it = specs().find(l.words[0]);
    if (it == specs().end()) throw file_error(name, line, "unknown command '" + l.words[0] + "' (see SCRIPT.md)");
    const Spec& s = it->second;
    const int nargs = static_cast<int>(l.words.size()) - 1;
    if (nargs < s.min_args || nargs > s.max_args)
      throw file_error(name, line, "'" + l.words[0] + "' takes " +
                                       (s.min_args == s.max_args ? std::to_string(s.min_args)
                                                                 : std::to_string(s.min_args) + ".." + std::to_string(s.max_args)) +
                                       " argument(s), got " + std::to_string(nargs) + "; usage: " + s.usage);
    const int numbers = s.numbers < 0 ? nargs : s.numbers;
    for (int i = 1; i <= numbers; ++i) {
      double x;
      if (!parse_number(l.words[i], x))
        throw file_error(name, line, "'" + l.words[i] + "' is not a finite number; usage: " + s.usage);
    }
    if (const auto hw = handle_words().find(l.words[0]); hw != handle_words().end()) {
      for (int i = 1; i <= nargs; ++i) {
        const auto& at = hw->second;
        if (at[0] != -1 && std::find(at.begin(), at.end(), i) == at.end()) {
          double x;  // the other arguments of these commands are numbers (drag's offset) or words
          if (l.words[0] == "drag" && !parse_number(l.words[i], x))
            throw file_error(name, line, "'" + l.words[i] + "' is not a finite number; usage: " + s.usage);
          continue;
        }
        double x;
        if (parse_number(l.words[i], x) && (x != std::floor(x) || x < 0))
          throw file_error(name, line, "'" + l.words[i] + "' is not a handle number or name; usage: " + s.usage);
      }
    }
    if (l.words[0] == "add-bone" && nargs % 3 != 0)
      throw file_error(name, line, "add-bone needs joint positions in threes (x y z), got " + std::to_string(nargs) + " numbers");
    if (l.words[0] == "save-frames" && nargs == 2) {
      double c;
      if (!parse_number(l.words[2], c) || c < 2 || c != std::floor(c) || c > 100000)
        throw file_error(name, line, "frame count '" + l.words[2] + "' must be an integer >= 2");
    }
    if (l.words[0] == "key-mesh" && nargs == 2) {
      double t;
      if (!parse_number(l.words[2], t))
        throw file_error(name, line, "'" + l.words[2] + "' is not a finite number; usage: " + s.usage);
    }
    if (l.words[0] == "set-inbetween") {
      try {
        parse_inbetween_method(l.words[2]);
      } catch (const Error& e) {
        throw file_error(name, line, e.what());
      }
    }
    if (l.words[0] == "shape-space-key") {
      if (l.words[1] != "linear" && l.words[1] != "arap")
        throw file_error(name, line, "the morph must be linear or arap, got '" + l.words[1] + "'; usage: " + s.usage);
      for (int i = 2; i <= nargs; ++i) {
        double x;
        if (!parse_number(l.words[i], x))
          throw file_error(name, line, "'" + l.words[i] + "' is not a finite number; usage: " + s.usage);
      }
    }
    if (l.words[0] == "export-gltf") {
      if (!ends_with(l.words[1], ".glb") && !ends_with(l.words[1], ".gltf"))
        throw file_error(name, line, "export-gltf writes .glb or .gltf, got '" + l.words[1] + "'");
      if (nargs == 2 && l.words[2] != "4" && l.words[2] != "8")
        throw file_error(name, line, "influences per vertex must be 4 or 8, got '" + l.words[2] + "'");
    }
    if (l.words[0].rfind("weights-", 0) == 0) {
      try {
        script_detail::check_weight_command(l);
      } catch (const Error& e) {
        throw file_error(name, line, std::string(e.what()) + "; usage: " + s.usage);
      }
    }
    out.push_back(std::move(l));
  }
  return out;
}

std::vector<ScriptLine> read_script(const std::string& path) {
  require_readable_file(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw file_error(path, 0, "cannot open");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_script(ss.str(), path);
}

TriMesh posed_surface(const Document& doc) {
  if (doc.keys().size() >= 2) return manifold_frame(document_manifold(doc), doc.time()).mesh;
  return still_frame(doc);
}

namespace {

// Surface, rig, bind and mask commands; false when the line is not one of them.
bool run_rig_command(Document& doc, const ScriptLine& l, const ScriptHost& host) {
  const std::string& cmd = l.words[0];
  if (cmd == "open") {
    const std::string& f = l.words[1];
    if (ends_with(f, ".json")) doc.load_scene(f);
    else doc.open_mesh(f);  // a new document
  } else if (cmd == "replace-surface") {
    doc.replace_surface(l.words[1]);
  } else if (cmd == "add-point") {
    doc.add_point({num(l, 1), num(l, 2), num(l, 3)});
  } else if (cmd == "add-bone") {
    std::vector<Eigen::Vector3d> joints;
    for (size_t i = 1; i + 2 < l.words.size(); i += 3) joints.push_back({num(l, i), num(l, i + 1), num(l, i + 2)});
    doc.add_bone_chain(joints);
  } else if (cmd == "load-skeleton") {
    doc.load_skeleton(l.words[1]);
  } else if (cmd == "load-cage") {
    doc.load_cage(l.words[1]);
  } else if (cmd == "pseudo-edge") {
    const int a = handle_arg(doc, l, 1), b = handle_arg(doc, l, 2);
    for (int h : {a, b})
      if (handle_ref(doc.rig(), h).kind != HandleKind::Point)
        throw Error(handle_name(doc.rig(), h) + " (" + std::to_string(h) + ") is not a point handle");
    doc.add_pseudo_edge(a, b);
  } else if (cmd == "bind") {
    if (host.bind) host.bind(doc);
    else run_bind_blocking(doc);
  } else if (cmd == "paint-mask" || cmd == "paint-dab") {
    // One dab of the Paint tool's brush (brush.h): paint-mask sets VALUE, paint-dab adds or erases.
    Brush brush{num(l, 4), num(l, 5), 0.0, BrushMode::Set};
    if (cmd == "paint-mask") {
      if (brush.strength < 0 || brush.strength > 1) throw Error("mask values are in [0, 1], got " + l.words[5]);
      if (l.words.size() > 6) brush.falloff = num(l, 6);
    } else {
      brush.falloff = num(l, 6);
      if (l.words.size() > 7 && l.words[7] != "erase") throw Error("the last word is 'erase' or nothing, got " + l.words[7]);
      brush.mode = l.words.size() > 7 ? BrushMode::Erase : BrushMode::Add;
    }
    if (brush.radius <= 0) throw Error("radius must be > 0");
    const BrushDab dab = brush_dab(doc.surface().V, doc.mask(), Eigen::Vector3d(num(l, 1), num(l, 2), num(l, 3)), brush);
    if (dab.vertices.empty()) throw Error("no surface vertex within " + l.words[4] + " of the point");
    doc.paint_mask(dab.vertices, dab.values);
  } else {
    return false;
  }
  return true;
}

// Selection, posing and undo commands; false when the line is not one of them.
bool run_pose_command(Document& doc, const ScriptLine& l, const std::function<void(const std::string&)>& print) {
  const std::string& cmd = l.words[0];
  if (cmd == "select") {
    Selection s;
    for (size_t i = 1; i < l.words.size(); ++i) s.handles.push_back(handle_arg(doc, l, static_cast<int>(i)));
    doc.set_selection(s);
  } else if (cmd == "translate") {
    const Eigen::Vector3d d(num(l, 1), num(l, 2), num(l, 3));
    for (int h : selected_or_fail(doc)) {
      const DragReport r = doc.translate_handle(h, d);
      if (r.kind != DragKind::Moved) print("translate: " + r.message);
    }
  } else if (cmd == "rotate") {
    const Eigen::Vector3d axis(num(l, 2), num(l, 3), num(l, 4));
    if (axis.norm() < 1e-12) throw Error("rotation axis is zero");
    const Eigen::Quaterniond q(Eigen::AngleAxisd(num(l, 1) * M_PI / 180.0, axis.normalized()));
    for (int h : selected_or_fail(doc)) doc.rotate_handle(h, q);
  } else if (cmd == "drag") {
    print("drag: " + doc.drag_handle(handle_arg(doc, l, 1), Eigen::Vector3d(num(l, 2), num(l, 3), num(l, 4))).message);
  } else if (cmd == "handle-state") {
    doc.set_handle_state(handle_arg(doc, l, 1), parse_constraint_state(l.words[2]));
  } else if (cmd == "ik-chain") {
    PosingSettings p = doc.posing();
    p.fast = true;
    p.states = ik_chain_states(doc.rig(), doc.handle_states(), handle_arg(doc, l, 1));
    doc.set_posing(p);
  } else if (cmd == "bind-monotone") {
    if (l.words[1] != "on" && l.words[1] != "off")
      throw Error("bind-monotone: expected on or off, got '" + l.words[1] + "'");
    BindSettings b = doc.bind_settings();
    b.monotone = l.words[1] == "on";
    doc.set_bind_settings(b);
  } else if (cmd == "fast") {
    if (l.words[1] != "on" && l.words[1] != "off") throw Error("fast: expected on or off, got '" + l.words[1] + "'");
    PosingSettings p = doc.posing();
    p.fast = l.words[1] == "on";
    if (l.words.size() > 2) {
      double n = 0;
      if (!parse_number(l.words[2], n) || n != std::floor(n)) throw Error("'" + l.words[2] + "' is not an iteration count");
      p.iterations = static_cast<int>(n);
    }
    doc.set_posing(p);
  } else if (cmd == "set-method") {
    doc.set_method(parse_skin_method(l.words[1]));
  } else if (cmd == "reset-pose") {
    doc.reset_pose();
  } else if (cmd == "undo") {
    doc.undo();
  } else if (cmd == "redo") {
    doc.redo();
  } else {
    return false;
  }
  return true;
}

// Key and time commands; false when the line is not one of them.
bool run_animation_command(Document& doc, const ScriptLine& l) {
  const std::string& cmd = l.words[0];
  if (cmd == "set-key") {
    doc.set_key(l.words.size() > 1 ? num(l, 1) : doc.time());
  } else if (cmd == "key-mesh") {
    doc.key_mesh_file(l.words[1], l.words.size() > 2 ? num(l, 2) : doc.time());
  } else if (cmd == "shape-space-key") {
    // Key times, then as many weights, then an optional time to key at (Alexa 2002, ch. 5).
    const int m = static_cast<int>(l.words.size()) - 2, n = m / 2;
    std::vector<double> times;
    Eigen::VectorXd x(n);
    for (int i = 0; i < n; ++i) times.push_back(num(l, 2 + i)), x(i) = num(l, 2 + n + i);
    ShapeSpace space = key_shape_space(doc, times, parse_shape_morph(l.words[1]));
    key_synthesized_shape(doc, space, x, m % 2 ? num(l, static_cast<int>(l.words.size()) - 1) : doc.time());
  } else if (cmd == "delete-key") {
    const double t = l.words.size() > 1 ? num(l, 1) : doc.time();
    const int k = doc.key_at(t);
    if (k < 0) throw Error("no key at time " + (l.words.size() > 1 ? l.words[1] : std::to_string(t)));
    doc.delete_key(k);
  } else if (cmd == "set-inbetween") {
    const int k = doc.key_at(num(l, 1));
    if (k < 0) throw Error("no key at time " + l.words[1]);
    doc.set_key_inbetween(k, parse_inbetween_method(l.words[2]));
  } else if (cmd == "set-time") {
    doc.set_time(num(l, 1));
  } else {
    return false;
  }
  return true;
}

// Commands that write files; false when the line is not one of them.
bool run_file_command(Document& doc, const ScriptLine& l, const ScriptHost& host) {
  const std::string& cmd = l.words[0];
  if (cmd == "save-posed") {
    write_surface(l.words[1], posed_surface(doc));
  } else if (cmd == "save-frames") {
    const int count = l.words.size() > 2 ? integer_arg(l, 2) : kDefaultFrameCount;
    if (doc.keys().size() < 2) throw Error("save-frames needs at least two keys");
    write_frame_sequence(document_manifold(doc), l.words[1], count);
  } else if (cmd == "save-scene") {
    doc.save_scene(l.words[1]);
  } else if (cmd == "screenshot") {
    if (!host.screenshot) throw Error("screenshots need the editor (no renderer here)");
    host.screenshot(l.words[1]);
  } else if (cmd == "export-gltf") {
    if (!host.export_gltf) throw Error("glTF export needs the editor (or `deform export`)");
    host.export_gltf(l.words[1], l.words.size() > 2 ? std::stoi(l.words[2]) : 4);
  } else {
    return false;
  }
  return true;
}

}  // namespace

ScriptResult run_script(Document& doc, const std::vector<ScriptLine>& lines, const std::string& name,
                        const ScriptHost& host) {
  ScriptResult res;
  const std::function<void(const std::string&)> print = host.print ? host.print : [](const std::string& s) {
    std::printf("%s\n", s.c_str());
    std::fflush(stdout);
  };
  for (const ScriptLine& l : lines) {
    const std::string& cmd = l.words[0];
    try {
      if (cmd == "quit") {
        res.quit = true;
      } else if (!run_rig_command(doc, l, host) && !run_pose_command(doc, l, print) && !run_animation_command(doc, l) &&
                 !run_file_command(doc, l, host)) {
        script_detail::run_weight_command(doc, l, print);
      }
    } catch (const Error& e) {
      throw file_error(name, l.line, cmd + ": " + e.what());
    }
    ++res.commands_run;
    if (host.after_command) host.after_command(l);
    if (res.quit) break;
  }
  return res;
}

}  // namespace dfm
