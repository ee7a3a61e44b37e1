// The rig as the viewport draws it: handle glyph positions as displayed (posed, or following the
// animation on a time slice), handle colours, and the overlay pass (bones, joints, cages, points, the
// selection's outline, FAST's state marks). Part of SceneView (scene_view.h).
#include <algorithm>
#include <cmath>

#include "app/editor/scene_view.h"
#include "app/editor/view_model.h"
#include "core/scene/key_pairs.h"
#include "core/rig/forward_kinematics.h"
#include "core/view/color.h"

namespace dfm::editor {

Eigen::Vector3f handle_color(int handle) {
  // Hues skip the band around the selection's orange (view_model.h), so a selected handle stands out;
  // fixed saturation and value. Linear, since the surface shader applies display gamma.
  const double hue = view::golden_hue(handle, kSelectionHueLo, kSelectionHueHi);
  return view::display_to_linear(view::hsv_to_rgb(hue, 0.62, 0.92).cast<float>());
}

std::vector<Eigen::Vector4f> blend_handle_colors(const Eigen::MatrixXd& W) {
  std::vector<Eigen::Vector3f> colors(W.cols());
  for (int j = 0; j < W.cols(); ++j) colors[j] = handle_color(j);
  std::vector<Eigen::Vector4f> out(W.rows(), Eigen::Vector4f(0, 0, 0, 1));
  for (int i = 0; i < W.rows(); ++i) {
    Eigen::Vector3f c = Eigen::Vector3f::Zero();
    double sum = 0;
    for (int j = 0; j < W.cols(); ++j) {
      const double w = std::max(0.0, W(i, j));
      c += static_cast<float>(w) * colors[j];
      sum += w;
    }
    if (sum > 0) c /= static_cast<float>(sum);
    out[i] = Eigen::Vector4f(c.x(), c.y(), c.z(), 1.0f);
  }
  return out;
}

void SceneView::update_handles(const Document& doc, const ViewSettings& s) {
  const Rig& rig = doc.rig();
  const int n = num_handles(rig);
  const Pose pose = pose_on_screen(doc, s.slice_axis);
  const bool posed = !display_is_rest_ && pose.size() == n;
  auto X = [&](int h, const Eigen::Vector3d& p) -> Eigen::Vector3d {
    return posed ? Eigen::Vector3d(pose.transforms[h] * p) : p;
  };
  handle_pos_.resize(n, 3);
  int h = 0;
  for (const PointHandle& p : rig.points) handle_pos_.row(h) = X(h, p.position), ++h;
  // Joints by core's one rule (posed_joints on the bones' transforms), so what is drawn is what skins.
  const int np = h, nb = rig.skeleton.num_bones();
  joint_pos_ = posed ? posed_joints(rig.skeleton, std::vector<Eigen::Affine3d>(pose.transforms.begin() + np,
                                                                               pose.transforms.begin() + np + nb))
                     : rig.skeleton.joints;
  for (const Bone& b : rig.skeleton.bones) handle_pos_.row(h++) = joint_pos_.row(b.a);
  for (const Cage& c : rig.cages)
    for (int v = 0; v < c.mesh.num_vertices(); ++v) handle_pos_.row(h) = X(h, c.mesh.V.row(v)), ++h;
  // Regions at their centroid on the rest surface (the document's pivot).
  for (size_t r = 0; r < rig.regions.size(); ++r, ++h) handle_pos_.row(h) = doc.handle_pivot(h).transpose();
}

namespace {

// How the rig's overlays are coloured this frame: faded over a mesh the rig does not apply to, the
// selection in its own body colour.
struct OverlayPaint {
  const std::vector<int>& sel;
  float alpha;
  Eigen::Vector4f sel_color, outline;
  bool selected(int h) const { return std::find(sel.begin(), sel.end(), h) != sel.end(); }
  Eigen::Vector4f faded(Eigen::Vector4f c) const { return c.w() *= alpha, c; }
  Eigen::Vector4f color_of(int h) const {
    if (selected(h)) return sel_color;
    // Overlays are not gamma-corrected: lift the linear colour back for display.
    const Eigen::Vector3f c = view::linear_to_display(handle_color(h));
    return faded(Eigen::Vector4f(c.x(), c.y(), c.z(), 1.0f));
  }
};

// The overlay's primitives, by how they are drawn. Selected handles get an outline: the same line or
// point, wider, in the outline colour, drawn under.
struct RigOverlay {
  std::vector<gl::OverlayVertex> lines, thin, pts, small_pts, outline_lines, outline_pts, outline_small;
  void line(std::vector<gl::OverlayVertex>& to, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
            const Eigen::Vector4f& ca, const Eigen::Vector4f& cb) {
    to.push_back(gl::overlay_vertex(a, ca));
    to.push_back(gl::overlay_vertex(b, cb));
  }
};

// Bones: a thick line from the bone's own first joint to its child joint; joints as small dots.
void add_bones(const Rig& rig, const Eigen::MatrixXd& P, const Eigen::MatrixXd& J, int sel_joint,
               const OverlayPaint& paint, RigOverlay& o) {
  const int np = num_point_handles(rig);
  for (int i = 0; i < rig.skeleton.num_bones(); ++i) {
    const Bone& b = rig.skeleton.bones[i];
    const int h = np + i;
    const Eigen::Vector4f c = paint.color_of(h);
    o.line(o.lines, P.row(h), J.row(b.b), c, Eigen::Vector4f(0.5f * c.x(), 0.5f * c.y(), 0.5f * c.z(), c.w()));
    if (paint.selected(h)) o.line(o.outline_lines, P.row(h), J.row(b.b), paint.outline, paint.outline);
  }
  const Eigen::Vector4f joint_color = paint.faded(Eigen::Vector4f(0.70f, 0.72f, 0.76f, 1.0f));
  for (int j = 0; j < J.rows(); ++j) {
    o.small_pts.push_back(gl::overlay_vertex(J.row(j), sel_joint == j ? paint.sel_color : joint_color));
    if (sel_joint == j) o.outline_small.push_back(gl::overlay_vertex(J.row(j), paint.outline));
  }
}

// Pseudo-edges between point handles, cage wireframes through the (posed) cage vertices, and the
// point-like glyphs (points, cage vertices, regions).
void add_points_and_cages(const Rig& rig, const Eigen::MatrixXd& P, const OverlayPaint& paint, RigOverlay& o) {
  const int np = num_point_handles(rig);
  const Eigen::Vector4f pseudo = paint.faded(Eigen::Vector4f(0.8f, 0.8f, 0.85f, 0.7f));
  for (const auto& [a, b] : rig.pseudo_edges)
    if (a >= 0 && b >= 0 && a < np && b < np) o.line(o.thin, P.row(a), P.row(b), pseudo, pseudo);
  int h0 = np + rig.skeleton.num_bones();
  const Eigen::Vector4f wire = paint.faded(Eigen::Vector4f(0.55f, 0.85f, 0.95f, 0.85f));
  for (const Cage& c : rig.cages) {
    auto edge = [&](int a, int b) { o.line(o.thin, P.row(h0 + a), P.row(h0 + b), wire, wire); };
    for (int f = 0; f < c.mesh.F.rows(); ++f)
      for (int k = 0; k < 3; ++k) edge(c.mesh.F(f, k), c.mesh.F(f, (k + 1) % 3));
    for (int e = 0; e < c.edges.rows(); ++e) edge(c.edges(e, 0), c.edges(e, 1));
    for (int v = 0; v < c.mesh.num_vertices(); ++v) {
      const bool sel = paint.selected(h0 + v);
      o.small_pts.push_back(gl::overlay_vertex(P.row(h0 + v), sel ? paint.sel_color : wire));
      if (sel) o.outline_small.push_back(gl::overlay_vertex(P.row(h0 + v), paint.outline));
    }
    h0 += c.mesh.num_vertices();
  }
  auto point = [&](int h) {
    o.pts.push_back(gl::overlay_vertex(P.row(h), paint.color_of(h)));
    if (paint.selected(h)) o.outline_pts.push_back(gl::overlay_vertex(P.row(h), paint.outline));
  };
  for (int i = 0; i < np; ++i) point(i);
  for (size_t r = 0; r < rig.regions.size(); ++r, ++h0)
    if (!rig.regions[r].vertices.empty()) point(h0);
}

void draw_rig_overlay(gl::RenderBackend& gpu, const view::Camera& cam, const RigOverlay& o, const SelectionStyle& style) {
  const float bone_w = 5.0f, small_sz = 8.0f, point_sz = 14.0f;
  gpu.draw_lines(cam, o.thin, 1.5f, false);
  if (!o.outline_lines.empty()) gpu.draw_lines(cam, o.outline_lines, bone_w + style.line_extra, false);
  gpu.draw_lines(cam, o.lines, bone_w, false);
  if (!o.outline_small.empty()) gpu.draw_points(cam, o.outline_small, small_sz + style.point_extra, false);
  gpu.draw_points(cam, o.small_pts, small_sz, false);
  if (!o.outline_pts.empty()) gpu.draw_points(cam, o.outline_pts, point_sz + style.point_extra, false);
  gpu.draw_points(cam, o.pts, point_sz, false);
}

// FAST states on the handles (bones: at the tip IK drags): a dark centre is pinned, a white one free.
std::vector<gl::OverlayVertex> fast_state_marks(const Document& doc, const Eigen::MatrixXd& P, const Eigen::MatrixXd& J,
                                                const OverlayPaint& paint) {
  std::vector<gl::OverlayVertex> marks;
  const Rig& rig = doc.rig();
  const std::vector<HandleConstraint> states = doc.handle_states();
  for (int k = 0; k < static_cast<int>(states.size()) && k < P.rows(); ++k) {
    if (states[k] == HandleConstraint::Position) continue;
    const HandleRef r = handle_ref(rig, k);
    const Eigen::Vector3d at = r.kind == HandleKind::Bone ? Eigen::Vector3d(J.row(rig.skeleton.bones[r.index].b))
                                                          : Eigen::Vector3d(P.row(k));
    const Eigen::Vector4f c = states[k] == HandleConstraint::Fixed ? Eigen::Vector4f(0.08f, 0.08f, 0.1f, 1.0f)
                                                                   : Eigen::Vector4f(1.0f, 1.0f, 1.0f, 1.0f);
    marks.push_back(gl::overlay_vertex(at, paint.faded(c)));
  }
  return marks;
}

// The picked pairs of the interval holding the current time (SceneKey::pairs_to_next): the point on
// the first key in its colour, its partner on the next in the other's, joined by a thin line; inside
// the interval, with the transition's placement, where each pair is now (pairs_now) in white.
void draw_picked_pairs(gl::RenderBackend& gpu, const view::Camera& cam, const Document& doc, const KeyPlacement* placement) {
  const auto& keys = doc.keys();
  if (keys.size() < 2) return;
  const Eigen::MatrixXd& P = keys[pair_interval(doc, doc.time())].pairs_to_next;
  if (P.rows() == 0) return;
  const Eigen::Vector4f from(1.0f, 0.62f, 0.2f, 1.0f), to(0.3f, 0.85f, 0.9f, 1.0f), white(1.0f, 1.0f, 1.0f, 1.0f);
  std::vector<gl::OverlayVertex> lines, pts, current;
  for (Eigen::Index r = 0; r < P.rows(); ++r) {
    const Eigen::Vector3d a = P.row(r).head<3>().transpose(), b = P.row(r).tail<3>().transpose();
    lines.push_back(gl::overlay_vertex(a, from));
    lines.push_back(gl::overlay_vertex(b, to));
    pts.push_back(gl::overlay_vertex(a, from));
    pts.push_back(gl::overlay_vertex(b, to));
  }
  const Eigen::MatrixXd now = pairs_now(doc, placement);
  for (Eigen::Index r = 0; r < now.rows(); ++r) current.push_back(gl::overlay_vertex(now.row(r).transpose(), white));
  gpu.draw_lines(cam, lines, 2.0f, false);
  gpu.draw_points(cam, pts, 10.0f, false);
  if (!current.empty()) gpu.draw_points(cam, current, 8.0f, false);
}

}  // namespace

void SceneView::draw_overlays(const Document& doc, const view::Camera& cam) {
  draw_picked_pairs(gpu_, cam, doc, pair_placement(doc));
  // Over a surface that is not the rigged mesh (a transition, a key of other triangles) the rig fades.
  if (overlay_opacity_ < kMinOverlayOpacity) return;
  const SelectionStyle& style = selection_style();
  OverlayPaint paint{doc.selection().handles, overlay_opacity_, style.body, style.outline};
  paint.sel_color = paint.faded(style.body);
  paint.outline = paint.faded(style.outline);
  RigOverlay o;
  add_bones(doc.rig(), handle_pos_, joint_pos_, doc.selection().joint, paint, o);
  add_points_and_cages(doc.rig(), handle_pos_, paint, o);
  draw_rig_overlay(gpu_, cam, o, style);
  if (doc.posing().fast) gpu_.draw_points(cam, fast_state_marks(doc, handle_pos_, joint_pos_, paint), 6.0f, false);
}

}  // namespace dfm::editor
