#include "app/editor/timeline_ruler.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/editor/view_model.h"
#include "render/overlay_geometry.h"

namespace dfm::editor {
namespace {

// Ticks on whole frames (1, 2 or 5 times a power of ten), labelled with the frame number, about one
// per 60 px; the animated span as a bar along the bottom.
void draw_ticks(ImDrawList* dl, const TimelineRuler::Span& s, const Document& doc, double frame_rate) {
  dl->AddRectFilled(ImVec2(s.x0, s.y0), ImVec2(s.x0 + s.w, s.y0 + s.h), IM_COL32(24, 25, 28, 255), 3.0f);
  const double frames = std::max(1e-9, (s.t1 - s.t0) * frame_rate);
  const double fstep = std::max(1.0, gl::nice_spacing(frames, std::max(2, int(s.w / 60))));
  for (double f = std::ceil(s.t0 * frame_rate / fstep) * fstep; f <= s.t1 * frame_rate + 1e-6; f += fstep) {
    const float x = s.x_of(f / frame_rate);
    dl->AddLine(ImVec2(x, s.y0), ImVec2(x, s.y0 + 8), IM_COL32(110, 114, 122, 255));
    char lab[16];
    std::snprintf(lab, sizeof lab, "%.0f", f);
    dl->AddText(ImVec2(x + 3, s.y0 + 1), IM_COL32(130, 134, 142, 255), lab);
  }
  const auto& keys = doc.keys();
  if (keys.size() >= 2)
    dl->AddRectFilled(ImVec2(s.x_of(keys.front().time), s.y0 + s.h - 10), ImVec2(s.x_of(keys.back().time), s.y0 + s.h - 6),
                      IM_COL32(70, 110, 170, 200), 2.0f);
}

void key_tooltip(const Document& doc, int k, double frame_rate) {
  const SceneKey& key = doc.keys()[k];
  const std::string next_join =
      k + 1 < int(doc.keys().size()) ? interval_join_label(interval_join(doc, k)) : "(the last key)";
  if (key.is_mesh())
    ImGui::SetTooltip("mesh key %d at %s: %s\n%d vertices, %d triangles\nto the next key: %s\n"
                      "(drag to move, right-click to delete)",
                      k, format_time(key.time, frame_rate).c_str(),
                      std::filesystem::path(key.mesh_path).filename().string().c_str(), key.mesh.num_vertices(),
                      key.mesh.num_faces(), next_join.c_str());
  else
    ImGui::SetTooltip("key %d at %s\nto the next key: %s\n(drag to move, right-click to delete)", k,
                      format_time(key.time, frame_rate).c_str(), next_join.c_str());
}

}  // namespace

void TimelineRuler::draw(Document& doc, double frame_rate, std::string& error) {
  Span s;
  const auto& keys = doc.keys();
  // Range: the keys' span padded, at least [0, 1], and the current time.
  if (!keys.empty()) {
    s.t0 = std::min(0.0, keys.front().time);
    s.t1 = std::max(1.0, keys.back().time);
  }
  s.t1 = std::max(s.t1, doc.time());
  const ImVec2 p0 = ImGui::GetCursorScreenPos();
  s.x0 = p0.x, s.y0 = p0.y;
  s.w = ImGui::GetContentRegionAvail().x, s.h = std::max(30.0f, ImGui::GetContentRegionAvail().y);
  ImDrawList* dl = ImGui::GetWindowDrawList();
  draw_ticks(dl, s, doc, frame_rate);
  for (const SpaceTimeEdit& e : doc.space_time_edits())  // where the motion was edited
    dl->AddRectFilled(ImVec2(s.x_of(e.region.t0), s.y0 + s.h * 0.75f), ImVec2(s.x_of(e.region.t1), s.y0 + s.h * 0.85f),
                      IM_COL32(190, 115, 255, 110));
  if (band_ && band_->first < band_->second)
    dl->AddRectFilled(ImVec2(s.x_of(band_->first), s.y0), ImVec2(s.x_of(band_->second), s.y0 + s.h),
                      IM_COL32(190, 115, 255, 45));
  const int hover_key = handle_input(doc, s, frame_rate, error);
  draw_keys(doc, s, hover_key);
  const float xt = s.x_of(doc.time());
  dl->AddLine(ImVec2(xt, s.y0), ImVec2(xt, s.y0 + s.h), IM_COL32(90, 160, 255, 255), 2.0f);
  dl->AddTriangleFilled(ImVec2(xt - 5, s.y0), ImVec2(xt + 5, s.y0), ImVec2(xt, s.y0 + 6), IM_COL32(90, 160, 255, 255));
  if (hover_key >= 0) key_tooltip(doc, hover_key, frame_rate);
}

int TimelineRuler::handle_input(Document& doc, const Span& s, double frame_rate, std::string& error) {
  const auto& keys = doc.keys();
  ImGui::InvisibleButton("ruler", ImVec2(s.w, s.h), ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
  const bool hovered = ImGui::IsItemHovered();
  const float mx = ImGui::GetIO().MousePos.x, my = ImGui::GetIO().MousePos.y;
  int hover_key = -1;
  for (size_t i = 0; i < keys.size(); ++i)
    if (hovered && std::abs(mx - s.x_of(keys[i].time)) < 7 && std::abs(my - s.key_y()) < 10) hover_key = int(i);
  // An edge of the band, when no key is under the cursor: 0 the start, 1 the end, -1 neither.
  int hover_edge = -1;
  if (hovered && hover_key < 0 && band_ && band_->first < band_->second) {
    const float d0 = std::abs(mx - s.x_of(band_->first)), d1 = std::abs(mx - s.x_of(band_->second));
    if (std::min(d0, d1) < 5) hover_edge = d0 <= d1 ? 0 : 1;
  }
  if (hover_edge >= 0 || drag_ == Drag::BandStart || drag_ == Drag::BandEnd) {
    ImGui::SetMouseCursor(ImGuiMouseCursor_ResizeEW);
    if (drag_ == Drag::None) ImGui::SetTooltip("drag to move the Space-time tool's window %s", hover_edge == 0 ? "start" : "end");
  }
  if (ImGui::IsItemClicked(ImGuiMouseButton_Left)) {
    drag_ = hover_key >= 0 ? Drag::Key : hover_edge == 0 ? Drag::BandStart : hover_edge == 1 ? Drag::BandEnd : Drag::Scrub;
    drag_key_ = hover_key;
  }
  if ((drag_ == Drag::BandStart || drag_ == Drag::BandEnd) && band_) {
    band_ = dragged_band(*band_, drag_ == Drag::BandStart ? 0 : 1, std::clamp(s.t_of(mx), s.t0, s.t1), frame_rate);
    if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) drag_ = Drag::None;
  }
  if (ImGui::IsItemClicked(ImGuiMouseButton_Right) && hover_key >= 0) {
    doc.delete_key(hover_key);
    hover_key = -1;  // gone: no tooltip for it
  }
  if (drag_ == Drag::Scrub) {
    doc.set_time(std::clamp(s.t_of(mx), 0.0, 1e9));
    if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) drag_ = Drag::None;
  }
  if (drag_ == Drag::Key) {
    const float x = std::clamp(mx, s.x0 + s.pad, s.x0 + s.w - s.pad);
    ImGui::GetWindowDrawList()->AddLine(ImVec2(x, s.y0), ImVec2(x, s.y0 + s.h), IM_COL32(255, 210, 90, 160));
    if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
      const double nt = std::max(0.0, std::round(s.t_of(x) * frame_rate) / frame_rate);  // snap to whole frames
      if (drag_key_ >= 0 && drag_key_ < int(keys.size()) && std::abs(nt - keys[drag_key_].time) > 1e-9) {
        try {
          doc.move_key(drag_key_, nt);
        } catch (const std::exception& e) {
          error = e.what();
        }
      }
      drag_ = Drag::None;
      drag_key_ = -1;
    }
  }
  return hover_key;
}

void TimelineRuler::draw_keys(const Document& doc, const Span& s, int hover_key) const {
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const auto& keys = doc.keys();
  const float ky = s.key_y();
  // Intervals with an ARAP or linear in-between: a bar between their keys (green, grey).
  for (size_t i = 0; i + 1 < keys.size(); ++i) {
    const InbetweenMethod m = keys[i].inbetween;
    if (m == InbetweenMethod::Handles) continue;
    const ImU32 c = m == InbetweenMethod::Arap ? IM_COL32(110, 200, 120, 200) : IM_COL32(150, 150, 150, 200);
    dl->AddLine(ImVec2(s.x_of(keys[i].time), ky), ImVec2(s.x_of(keys[i + 1].time), ky), c, 3.0f);
  }
  // Pose keys are amber diamonds, mesh keys teal squares.
  for (size_t i = 0; i < keys.size(); ++i) {
    const float x = s.x_of(keys[i].time), r = 6;
    const bool hot = int(i) == hover_key || int(i) == drag_key_;
    if (keys[i].is_mesh()) {
      const float q = r - 1;
      dl->AddRectFilled(ImVec2(x - q, ky - q), ImVec2(x + q, ky + q),
                        hot ? IM_COL32(150, 240, 235, 255) : IM_COL32(70, 195, 190, 255), 1.5f);
    } else {
      const ImU32 c = hot ? IM_COL32(255, 220, 110, 255) : IM_COL32(235, 180, 60, 255);
      dl->AddQuadFilled(ImVec2(x, ky - r), ImVec2(x + r, ky), ImVec2(x, ky + r), ImVec2(x - r, ky), c);
    }
  }
}

}  // namespace dfm::editor
