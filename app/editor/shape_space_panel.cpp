// The Shape space panel (Alexa 2002, ch. 5): keys chosen as bases sit as points on a 2D pad; dragging
// the cursor synthesizes the shape at its barycentric coordinates in the pad's Delaunay triangulation
// (core/anim/shape_space_pad.h) by Eq. 5.31's chain of linear or ARAP morphs, shown in the viewport;
// "Key this shape" keys it as a mesh (core/scene/shape_space_keys.h, what the script's
// shape-space-key does). Pad points are dragged to rearrange the space. Linear follows the cursor;
// ARAP (seconds: TetGen and factorizations per base once, then about a second a shape on the teddy)
// is requested when the cursor is released and runs on a worker thread (shape_space_cursor.h), the
// linear blend standing in until the shape for the cursor arrives; a newer cursor or Cancel
// supersedes it, and "Key this shape" is disabled until it is there.
#include "app/editor/shape_space_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "app/editor/editor.h"
#include "core/scene/shape_space_keys.h"
#include "core/util/error.h"

namespace dfm::editor {

Eigen::Vector2d default_pad_point(int i, int n) {
  if (n <= 2) return Eigen::Vector2d(i == 0 ? 0.15 : 0.85, 0.5);
  const double a = -M_PI / 2 + 2 * M_PI * i / n;  // the first base at the top
  return Eigen::Vector2d(0.5 + 0.4 * std::cos(a), 0.5 + 0.4 * std::sin(a));
}

namespace {

// "0:1:2" -> {0, 1, 2}.
std::vector<double> parse_list(const std::string& v, const std::string& key) {
  std::vector<double> out;
  std::stringstream in(v);
  for (std::string w; std::getline(in, w, ':');) {
    char* end = nullptr;
    const double x = std::strtod(w.c_str(), &end);
    if (w.empty() || *end != '\0' || !std::isfinite(x)) throw Error("--ui: bad value '" + v + "' for " + key);
    out.push_back(x);
  }
  return out;
}

std::string key_label(const Document& doc, int k) {
  const SceneKey& key = doc.keys()[k];
  char buf[96];
  if (key.is_mesh()) {
    const size_t slash = key.mesh_path.find_last_of('/');
    std::snprintf(buf, sizeof buf, "%s (t = %g)", key.mesh_path.substr(slash == std::string::npos ? 0 : slash + 1).c_str(),
                  key.time);
  } else {
    std::snprintf(buf, sizeof buf, "pose key (t = %g)", key.time);
  }
  return buf;
}

void add_base(ShapeSpacePanel& p, double t) {
  p.times.push_back(t);
  const int n = static_cast<int>(p.times.size());
  p.points.conservativeResize(n, 2);
  for (int i = 0; i < n; ++i) p.points.row(i) = default_pad_point(i, n).transpose();
}

void text_disabled_wrapped(const char* text) {
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("%s", text);
  ImGui::PopStyleColor();
}

// Where the shown shape stands: final (and its time), or ARAP on the worker (elapsed, Cancel), or
// cancelled (Synthesize asks again).
void shape_space_synthesis_status(CursorShape& c, bool arap) {
  if (c.is_final()) {
    if (arap) ImGui::TextDisabled("synthesized (ARAP) in %.2f s", c.synth_ms() / 1000.0);
    else ImGui::TextDisabled("synthesized in %.2f ms", c.synth_ms());
  } else if (c.waiting()) {
    ImGui::Text("synthesizing (ARAP)... %.1f s", c.elapsed_seconds());
    ImGui::SameLine();
    if (ImGui::SmallButton("Cancel##ssarap")) c.cancel();
    text_disabled_wrapped("the viewport shows the linear blend until it is done");
  } else if (c.cancelled()) {
    if (ImGui::SmallButton("Synthesize##ssarap")) c.retry();  // asked for again next frame
    ImGui::SameLine();
    text_disabled_wrapped("ARAP cancelled: linear blend shown");
  } else if (arap && !c.error().empty()) {
    text_disabled_wrapped("ARAP failed (below): linear blend shown");
  } else if (arap) {
    text_disabled_wrapped("linear blend while dragging; ARAP on release");
  }
  if (arap && c.running() && !c.waiting()) text_disabled_wrapped("(the worker finishes a superseded synthesis)");
}

void remove_base(ShapeSpacePanel& p, int i) {
  p.times.erase(p.times.begin() + i);
  PadPoints kept(p.points.rows() - 1, 2);
  for (int r = 0, k = 0; r < p.points.rows(); ++r)
    if (r != i) kept.row(k++) = p.points.row(r);
  p.points = kept;
}

// One checkbox per key: on makes it a base (numbered in chain order), off removes it.
void draw_bases(ShapeSpacePanel& p, const Document& doc) {
  ImGui::TextDisabled("bases (keys, in chain order):");
  for (int k = 0; k < static_cast<int>(doc.keys().size()); ++k) {
    const double t = doc.keys()[k].time;
    const auto it = std::find(p.times.begin(), p.times.end(), t);
    bool on = it != p.times.end();
    char label[128];
    std::snprintf(label, sizeof label, "%s%s##ssk%d", on ? std::to_string(it - p.times.begin()).c_str() : "-",
                  (": " + key_label(doc, k)).c_str(), k);
    if (ImGui::Checkbox(label, &on)) {
      if (on) add_base(p, t);
      else remove_base(p, static_cast<int>(it - p.times.begin()));
    }
  }
  if (doc.keys().size() < 2) ImGui::TextDisabled("key two or more poses or meshes first");
  if (!p.times.empty() && ImGui::SmallButton("Clear bases")) p.times.clear(), p.points.resize(0, 2);
}

// The barycentric weights at the cursor, the ARAP synthesis status, and what failed.
// "Key this shape" as a script line: the bases' times, the cursor's coordinates, the key's time.
CommandWords shape_space_key_words(const ShapeSpacePanel& p) {
  CommandWords w = command_words("shape-space-key", {shape_morph_name(p.morph)});
  for (double t : p.times) w.push_back(CommandArg(t).word);
  for (Eigen::Index i = 0; i < p.weights.size(); ++i) w.push_back(CommandArg(p.weights(i)).word);
  w.push_back(CommandArg(p.key_time).word);
  return w;
}

void draw_weights_and_errors(ShapeSpacePanel& p, bool have_shape) {
  CursorShape& c = p.shape;
  if (p.weights.size() == static_cast<Eigen::Index>(p.times.size()) && p.times.size() >= 2) {
    std::string w = "weights:";
    for (int i = 0; i < p.weights.size(); ++i) {
      char b[24];
      std::snprintf(b, sizeof b, " %d:%.2f", i, p.weights(i));
      w += b;
    }
    ImGui::TextWrapped("%s", w.c_str());
    if (have_shape) shape_space_synthesis_status(c, p.space->morph() == ShapeMorph::Arap);
  }
  for (const std::string* e : std::initializer_list<const std::string*>{&p.build_error, &c.error()})
    if (!e->empty()) {
      ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.95f, 0.45f, 0.35f, 1));
      ImGui::TextWrapped("%s", e->substr(0, 300).c_str());
      ImGui::PopStyleColor();
    }
}

}  // namespace

bool Editor::shape_space_ui_option(const std::string& key, const std::string& value) {
  ShapeSpacePanel& p = *shape_space_;
  if (key == "shape_space") {  // key times, e.g. 0:1:2 (the keys may come from the script)
    p.times.clear();
    p.points.resize(0, 2);
    for (double t : parse_list(value, key)) add_base(p, t);
    p.open_request = true;
  } else if (key == "shape_cursor") {  // pad coordinates u:v in [0, 1]
    const std::vector<double> c = parse_list(value, key);
    if (c.size() != 2) throw Error("--ui: shape_cursor takes u:v, got '" + value + "'");
    p.cursor = Eigen::Vector2d(c[0], c[1]);
  } else if (key == "shape_morph") {
    p.morph = parse_shape_morph(value);
  } else {
    return false;
  }
  return true;
}

void Editor::update_shape_space() {
  ShapeSpacePanel& p = *shape_space_;
  if (p.built_revision == doc_.revision() && p.built_times == p.times && p.built_morph == p.morph) return;
  p.built_revision = doc_.revision();
  p.built_times = p.times;
  p.built_morph = p.morph;
  p.build_error.clear();
  if (p.times.size() < 2) {
    p.space.reset();
    return;
  }
  try {
    auto next = std::make_shared<ShapeSpace>(key_shape_space(doc_, p.times, p.morph));
    // The same bases and morph (a pose edit elsewhere): keep the old space and its ARAP setups.
    auto equal = [](const auto& a, const auto& b) { return a.rows() == b.rows() && a.cols() == b.cols() && a == b; };
    bool same = p.space && p.space->morph() == next->morph() && p.space->size() == next->size() &&
                equal(p.space->faces(), next->faces());
    for (int i = 0; same && i < next->size(); ++i) same = equal(p.space->bases()[i], next->bases()[i]);
    if (!same) p.space = std::move(next);  // the cursor's shape starts afresh (CursorShape::update)
  } catch (const std::exception& e) {
    p.space.reset();
    p.build_error = e.what();
  }
}

// The pad: points (drag to move), the Delaunay triangulation, the cursor (drag; snaps to a point).
void Editor::shape_space_pad(ShapeSpacePanel& p) {
  const float side = std::min(ImGui::GetContentRegionAvail().x, 260.0f);
  const ImVec2 o = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("##pad", ImVec2(side, side));
  const bool activated = ImGui::IsItemActivated(), active = ImGui::IsItemActive();
  const int n = static_cast<int>(p.points.rows());
  auto to_screen = [&](const Eigen::Vector2d& q) { return ImVec2(o.x + float(q.x()) * side, o.y + float(q.y()) * side); };
  const ImVec2 m = ImGui::GetIO().MousePos;
  const Eigen::Vector2d mouse(std::clamp((m.x - o.x) / side, 0.0f, 1.0f), std::clamp((m.y - o.y) / side, 0.0f, 1.0f));
  auto nearest_point = [&](double px) {
    for (int i = 0; i < n; ++i)
      if (((p.points.row(i).transpose() - mouse) * side).norm() <= px) return i;
    return -1;
  };
  if (activated) p.dragging_point = ImGui::GetIO().KeyShift ? -1 : nearest_point(9);
  if (active) {
    if (p.dragging_point >= 0) p.points.row(p.dragging_point) = mouse.transpose();
    else {
      const int snap = nearest_point(6);  // a base's own point: that base exactly
      p.cursor = snap >= 0 ? Eigen::Vector2d(p.points.row(snap).transpose()) : mouse;
    }
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("drag the cursor to blend the bases; drag a base's point to move it");

  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->AddRectFilled(o, ImVec2(o.x + side, o.y + side), IM_COL32(28, 30, 36, 255), 4.0f);
  dl->AddRect(o, ImVec2(o.x + side, o.y + side), IM_COL32(80, 84, 96, 255), 4.0f);
  if (n >= 2) {
    const std::vector<std::array<int, 3>> tris = pad_triangles(p.points);
    for (const auto& t : tris)
      for (int k = 0; k < 3; ++k)
        dl->AddLine(to_screen(p.points.row(t[k]).transpose()), to_screen(p.points.row(t[(k + 1) % 3]).transpose()),
                    IM_COL32(90, 110, 140, 255), 1.0f);
    if (tris.empty())  // collinear: the segments between neighbours along the line
      for (int i = 0; i + 1 < n; ++i)
        dl->AddLine(to_screen(p.points.row(i).transpose()), to_screen(p.points.row(i + 1).transpose()),
                    IM_COL32(90, 110, 140, 255), 1.0f);
  }
  for (int i = 0; i < n; ++i) {
    const ImVec2 c = to_screen(p.points.row(i).transpose());
    const float w = p.weights.size() == n ? float(p.weights(i)) : 0.0f;
    dl->AddCircleFilled(c, 5.0f + 5.0f * w, IM_COL32(80 + int(150 * w), 170, 230 - int(120 * w), 255));
    char label[16];
    std::snprintf(label, sizeof label, "%d", i);
    dl->AddText(ImVec2(c.x + 8, c.y - 16), IM_COL32(220, 220, 230, 255), label);
  }
  if (n >= 2) {
    const Eigen::Vector2d at = pad_position(p.points, p.weights.size() == n ? p.weights : Eigen::VectorXd::Unit(n, 0));
    const ImVec2 c = to_screen(at), raw = to_screen(p.cursor);
    if (std::abs(c.x - raw.x) + std::abs(c.y - raw.y) > 1) dl->AddLine(raw, c, IM_COL32(200, 200, 200, 120), 1.0f);
    dl->AddCircle(c, 7.0f, IM_COL32(255, 210, 80, 255), 0, 2.0f);
    dl->AddLine(ImVec2(c.x - 11, c.y), ImVec2(c.x + 11, c.y), IM_COL32(255, 210, 80, 255), 1.5f);
    dl->AddLine(ImVec2(c.x, c.y - 11), ImVec2(c.x, c.y + 11), IM_COL32(255, 210, 80, 255), 1.5f);
  }
}

void Editor::draw_shape_space_section() {
  ShapeSpacePanel& p = *shape_space_;
  if (p.open_request) ImGui::SetNextItemOpen(true);
  if (!ImGui::CollapsingHeader("Shape space")) {
    view_->clear_preview();
    p.shape.pause();  // ARAP is asked for again when it opens
    return;
  }
  if (p.open_request) ImGui::SetScrollHereY(0.0f);  // --ui shape_space=...: in view once it has a space
  int morph = p.morph == ShapeMorph::Linear ? 0 : 1;
  ImGui::RadioButton("Linear", &morph, 0);
  ImGui::SameLine();
  ImGui::RadioButton("As rigid as possible", &morph, 1);
  p.morph = morph == 0 ? ShapeMorph::Linear : ShapeMorph::Arap;

  draw_bases(p, doc_);

  update_shape_space();
  if (p.times.size() >= 2) {
    try {
      p.weights = pad_weights(p.points, p.cursor);
    } catch (const std::exception& e) {
      p.build_error = e.what();
    }
  }
  if (p.space) p.open_request = false;
  shape_space_pad(p);
  const bool dragging = ImGui::IsItemActive();

  // Linear follows the cursor; ARAP runs on the worker once the cursor is released.
  CursorShape& c = p.shape;
  const bool changed = c.update(p.space, p.weights, dragging);
  const bool have_shape = p.space && c.vertices().rows() > 0 && c.weights().size() == p.space->size();
  if (p.preview && have_shape && (changed || !view_->showing_preview()))
    view_->show_preview(TriMesh{c.vertices(), p.space->faces(), {}});
  if (!p.preview || !have_shape) view_->clear_preview();

  draw_weights_and_errors(p, have_shape);
  ImGui::Checkbox("Show in viewport", &p.preview);

  if (!p.key_time_set) p.key_time = doc_.time();
  ImGui::SetNextItemWidth(90);
  if (ImGui::InputDouble("##sskt", &p.key_time, 0, 0, "t = %.3f")) p.key_time_set = true;
  ImGui::SameLine();
  // The shape keyed is the one shown, once it is the morph's own for the cursor (an ARAP one still on
  // the worker: disabled until it arrives); it is what core's synthesize returns for these weights.
  const bool can_key = have_shape && c.final_at(p.weights);
  if (!can_key) ImGui::BeginDisabled();
  if (ImGui::Button("Key this shape", ImVec2(-1, 0)) && can_key) {
    if (run_ui_command(shape_space_key_words(p))) p.key_time_set = false;
  }
  if (!can_key) ImGui::EndDisabled();
  if (!can_key && c.waiting() && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("waits for the ARAP shape at the cursor");
}

Eigen::MatrixXd Editor::shape_space_ready(const std::vector<double>& times, ShapeMorph morph,
                                          const Eigen::VectorXd& x) const {
  const ShapeSpacePanel& p = *shape_space_;
  if (!p.space || p.times != times || p.space->morph() != morph || !p.shape.final_at(x)) return {};
  return p.shape.vertices();
}

std::string Editor::shape_space_progress() const {
  const ShapeSpacePanel& p = *shape_space_;
  if (!p.shape.waiting()) return "";
  char buf[64];
  std::snprintf(buf, sizeof buf, "synthesizing (ARAP) %.1f s", p.shape.elapsed_seconds());
  return buf;
}

}  // namespace dfm::editor
