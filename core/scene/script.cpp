#include "core/scene/script.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/anim/manifold.h"
#include "core/anim/manifold_frame.h"
#include "core/scene/key_surfaces.h"
#include "core/skin/skin.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"

namespace dfm {

namespace {

TriMesh skinned(const Document& doc, const SkinBinding& binding, const PoseParams& params) {
  TriMesh out;
  SkinResult r = skin(doc.method(), binding, doc.skin_pose(params), stbs_handles(doc.rig(), params.bone_twist_stretch));
  out.V = std::move(r.V);
  out.F = doc.surface().F;
  out.N = std::move(r.N);
  return out;
}

SkinBinding binding_of(const Document& doc) {
  if (!doc.has_weights()) throw Error("the scene has no weights: " + doc.weights_note() + " (run: bind)");
  return make_skin_binding(doc.surface().V, vertex_normals(doc.surface().V, doc.surface().F), doc.weights(),
                           doc.rig(), doc.bind_settings().max_influences, doc.skin_endpoints(), doc.additional_weights());
}

// The frame without an animation (fewer than two keys): the one key (its mesh, or its pose skinned),
// else the current pose skinned with the current method.
TriMesh still_frame(const Document& doc) {
  if (doc.keys().size() == 1 && doc.keys()[0].is_mesh()) return doc.keys()[0].mesh;
  const SkinBinding binding = binding_of(doc);
  return skinned(doc, binding, doc.keys().size() == 1 ? doc.keys()[0].params : doc.pose_params());
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
    try {
      check_command(l.words);  // the command table's checks: every line before anything runs
    } catch (const Error& e) {
      throw file_error(name, line, e.what());
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
  if (doc.keys().size() >= 2) {  // held at the first key before it and at the last after it
    const double t = std::clamp(doc.time(), doc.keys().front().time, doc.keys().back().time);
    return manifold_frame(document_manifold(doc), t).mesh;
  }
  return still_frame(doc);
}

ScriptResult run_script(Document& doc, const std::vector<ScriptLine>& lines, const std::string& name,
                        const ScriptHost& host) {
  ScriptResult res;
  for (const ScriptLine& l : lines) {
    try {
      res.quit = run_checked(*find_command(l.words[0]), doc, l.words, host);  // parse_script checked it
    } catch (const Error& e) {
      throw file_error(name, l.line, l.words[0] + ": " + e.what());
    }
    ++res.commands_run;
    if (host.after_command) host.after_command(l);
    if (res.quit) break;
  }
  return res;
}

}  // namespace dfm
