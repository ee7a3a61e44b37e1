#include "app/editor/view_model.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/util/atomic_file.h"
#include "core/rig/handle_constraint.h"
#include "core/rig/rig.h"
#include "core/anim/transition.h"
#include "core/scene/key_pairs.h"
#include "core/scene/scene_import.h"

namespace dfm::editor {

PanelLayout layout_panels(double width, double height, double top, double timeline_h, double scale) {
  // Wide windows: 250 and 320 px; narrower ones take a share of the width, down to what the panels'
  // widgets need; below that the viewport keeps at least 40% and the panels share the rest.
  double left = std::round(std::clamp(0.19 * width, 200.0 * scale, 250.0 * scale));
  double right = std::round(std::clamp(0.25 * width, 270.0 * scale, 320.0 * scale));
  const double panels = std::max(0.0, 0.6 * width);
  if (left + right > panels && left + right > 0) {
    const double f = panels / (left + right);
    left = std::floor(left * f), right = std::floor(right * f);
  }
  PanelLayout l;
  const double body = std::max(1.0, height - top);
  l.left = Rect{0, top, left, body};
  l.right = Rect{width - right, top, right, body};
  const double middle = std::max(1.0, width - left - right);
  const double th = std::min(timeline_h, 0.5 * body);
  l.timeline = Rect{left, height - th, middle, th};
  l.viewport = Rect{left, top, middle, std::max(1.0, body - th)};
  return l;
}

int FlowCursor::place(double width) {
  if (x > 0 && x + spacing + width > avail) ++row, x = 0;
  x += (x > 0 ? spacing : 0.0) + width;
  return row;
}

std::vector<int> flow_rows(const std::vector<double>& widths, double avail, double spacing) {
  FlowCursor c{avail, spacing};
  std::vector<int> rows;
  for (double w : widths) rows.push_back(c.place(w));
  return rows;
}

std::string unopenable_reason(const std::string& path) {
  const std::string ext = file_extension(path);
  for (const char* e : {"json", "obj", "off", "ply", "stl", "mesh", "node", "ele", "tgf"})
    if (ext == e) return "";
  if (scene_importer_for(path) || motion_importer_for(path)) return "";  // rigged glTF, FBX, Collada; BVH motion
  std::string why = ext.empty() ? "'" + path + "' has no file extension"
                                : "the editor cannot open '." + ext + "' files";
  return why + ". It opens scenes (.scene.json), rigged glTF, FBX and Collada (.glb .gltf .fbx .dae), surfaces (.obj .off "
               ".ply .stl), tet meshes (.mesh, .node/.ele), skeletons (.tgf) and BVH motion onto the rig (.bvh); File > "
               "Load cage takes any surface file.";
}

namespace {

// The triangles key k's surface has: a mesh key's own, a pose key's the rigged surface's.
const TriMesh& key_mesh(const Document& doc, int k) {
  const SceneKey& key = doc.keys()[k];
  return key.is_mesh() ? key.mesh : doc.surface();
}

bool same_triangles(const TriMesh& a, const TriMesh& b) {
  return a.num_vertices() == b.num_vertices() && a.F.rows() == b.F.rows() && a.F == b.F;
}

}  // namespace

IntervalJoin interval_join(const Document& doc, int k) {
  if (!same_triangles(key_mesh(doc, k), key_mesh(doc, k + 1))) return IntervalJoin::Transition;
  switch (doc.keys()[k].inbetween) {
    case InbetweenMethod::Arap: return IntervalJoin::Arap;
    case InbetweenMethod::Linear: return IntervalJoin::Linear;
    default: return IntervalJoin::Handles;
  }
}

const char* interval_join_label(IntervalJoin join) {
  switch (join) {
    case IntervalJoin::Arap: return "ARAP";
    case IntervalJoin::Linear: return "linear";
    case IntervalJoin::Transition: return "transition (different meshes)";
    default: return "handles";
  }
}

int interval_at(const Document& doc, double t) {
  const auto& keys = doc.keys();
  if (keys.size() < 2 || t < keys.front().time - 1e-9 || t > keys.back().time + 1e-9) return -1;
  int k = 0;
  for (size_t i = 0; i + 1 < keys.size(); ++i)
    if (keys[i].time <= t + 1e-9) k = static_cast<int>(i);
  return k;
}

bool key_is_rigged(const Document& doc, int k) {
  return !doc.keys()[k].is_mesh() || same_triangles(doc.keys()[k].mesh, doc.surface());
}

Eigen::MatrixXd pairs_now(const Document& doc, const KeyPlacement* placement) {
  if (!placement || doc.keys().size() < 2) return Eigen::MatrixXd(0, 3);
  const int k = pair_interval(doc, doc.time());
  const SceneKey &a = doc.keys()[k], &b = doc.keys()[k + 1];
  const double u = (doc.time() - a.time) / (b.time - a.time);
  if (!(u > 0 && u < 1)) return Eigen::MatrixXd(0, 3);
  Eigen::MatrixXd now(a.pairs_to_next.rows(), 3);
  for (Eigen::Index r = 0; r < now.rows(); ++r) now.row(r) = pair_position(*placement, a.pairs_to_next.row(r), u);
  return now;
}

std::vector<ViewportLabel> pair_labels(const Document& doc, const view::Camera& cam, const KeyPlacement* placement,
                                       double offset) {
  std::vector<ViewportLabel> out;
  if (doc.keys().size() < 2) return out;
  const Eigen::MatrixXd& P = doc.keys()[pair_interval(doc, doc.time())].pairs_to_next;
  const Eigen::MatrixXd now = pairs_now(doc, placement);
  auto label = [&](const Eigen::Vector3d& x, const std::string& text) {
    const Eigen::Vector3d px = view::project_to_pixel(cam, x);
    if (std::abs(px.z()) <= 1) out.push_back({text, px.x() + offset, px.y() - offset});
  };
  for (Eigen::Index r = 0; r < P.rows(); ++r) {
    const std::string n = std::to_string(r + 1);
    label(P.row(r).head<3>().transpose(), n);
    label(P.row(r).tail<3>().transpose(), n);
    if (now.rows() > 0) label(now.row(r).transpose(), n);
  }
  return out;
}

float rig_overlay_opacity(const Document& doc, double t) {
  const auto& keys = doc.keys();
  if (keys.size() < 2) return 1.0f;  // no animation: the pose (or rest) is shown
  const double eps = 1e-9;
  // At or outside the keys' span the slice is the nearest key's surface.
  if (t <= keys.front().time + eps) return key_is_rigged(doc, 0) ? 1.0f : 0.0f;
  const int last = static_cast<int>(keys.size()) - 1;
  if (t >= keys.back().time - eps) return key_is_rigged(doc, last) ? 1.0f : 0.0f;
  const int k = interval_at(doc, t);
  if (std::abs(t - keys[k].time) <= eps) return key_is_rigged(doc, k) ? 1.0f : 0.0f;
  if (std::abs(t - keys[k + 1].time) <= eps) return key_is_rigged(doc, k + 1) ? 1.0f : 0.0f;
  if (interval_join(doc, k) != IntervalJoin::Transition) return 1.0f;
  const double s = (t - keys[k].time) / (keys[k + 1].time - keys[k].time);
  const double a = (key_is_rigged(doc, k) ? 1.0 - s : 0.0) + (key_is_rigged(doc, k + 1) ? s : 0.0);
  return static_cast<float>(std::clamp(a, 0.0, 1.0));
}

std::string outliner_label(const Document& doc, int h, bool with_state) {
  std::string s = std::to_string(h) + "  " + handle_name(doc.rig(), h);
  if (with_state && doc.posing().fast) {
    const std::vector<HandleConstraint> states = doc.handle_states();
    if (h >= 0 && h < static_cast<int>(states.size())) s += std::string("  [") + constraint_state_name(states[h]) + "]";
  }
  return s;
}

double display_value(double v, int decimals) {
  const double scale = std::pow(10.0, decimals);
  const double r = std::round(v * scale) / scale;
  return r == 0.0 ? 0.0 : r;  // -0.0 == 0.0: returns +0
}

double time_to_frame(double t, double fps) { return t * fps; }

std::string format_time(double t, double fps) {
  const double f = display_value(time_to_frame(t, fps), 1);
  char buf[64];
  if (f == std::round(f)) std::snprintf(buf, sizeof buf, "frame %.0f  (%.3f s)", f, display_value(t, 3));
  else std::snprintf(buf, sizeof buf, "frame %.1f  (%.3f s)", f, display_value(t, 3));
  return buf;
}

const SelectionStyle& selection_style() {
  static const SelectionStyle s;
  return s;
}

}  // namespace dfm::editor
