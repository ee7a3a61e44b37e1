#include "core/scene/space_time_edit.h"

#include <cmath>

#include "core/anim/manifold_normals.h"
#include "core/util/error.h"

namespace dfm {

bool SpaceTimeEdit::same_setup(const SpaceTimeEdit& o) const {
  return region.center == o.region.center && region.radius == o.region.radius && region.t0 == o.region.t0 &&
         region.t1 == o.region.t1 && handle.point == o.handle.point && handle.time == o.handle.time &&
         weights == o.weights && time_scale == o.time_scale && preserve_volume == o.preserve_volume;
}

bool SpaceTimeEdit::operator==(const SpaceTimeEdit& o) const {
  return same_setup(o) && move == o.move && rotation.coeffs() == o.rotation.coeffs();
}

void check_space_time_edit(const SpaceTimeEdit& e) {
  if (!e.region.center.allFinite() || !std::isfinite(e.region.radius) || !(e.region.radius > 0))
    throw Error("space-time edit: the region needs a finite centre and a positive radius");
  if (!std::isfinite(e.region.t0) || !std::isfinite(e.region.t1) || !(e.region.t0 < e.region.t1))
    throw Error("space-time edit: the time window needs T0 < T1");
  if (!e.handle.point.allFinite() || !std::isfinite(e.handle.time))
    throw Error("space-time edit: the handle is not finite");
  if (e.handle.time < e.region.t0 || e.handle.time > e.region.t1)
    throw Error("space-time edit: the handle's time " + std::to_string(e.handle.time) + " is outside the window [" +
                std::to_string(e.region.t0) + ", " + std::to_string(e.region.t1) + "]");
  if (!e.move.allFinite() || !e.rotation.coeffs().allFinite() || std::abs(e.rotation.norm() - 1) > 1e-9)
    throw Error("space-time edit: the move is not finite or the rotation not a unit quaternion");
  if (!std::isfinite(e.time_scale) || !(e.time_scale > 0))
    throw Error("space-time edit: the time scale must be positive");
}

struct SpaceTimeEditCache::Entry {
  SpaceTimeEdit setup;
  MatrixX4dRow input;  // the vertices the editor was initialised on
  std::unique_ptr<ManifoldEditor> editor;
};

SpaceTimeEditCache::SpaceTimeEditCache() = default;
SpaceTimeEditCache::~SpaceTimeEditCache() = default;

namespace {

std::unique_ptr<ManifoldEditor> make_editor(const AnimationManifold& m, const SpaceTimeEdit& e) {
  ManifoldEditOptions o;
  o.weights = e.weights;
  o.time_scale = e.time_scale;
  o.preserve_volume = e.preserve_volume;
  return std::make_unique<ManifoldEditor>(m, select_edit_region(m, e.region, e.handle), e.handle.point, o);
}

}  // namespace

std::vector<std::string> apply_space_time_edits(AnimationManifold& m, const std::vector<SpaceTimeEdit>& edits,
                                                SpaceTimeEditCache* cache) {
  std::vector<std::string> notes;
  if (cache && cache->entries.size() > edits.size()) cache->entries.resize(edits.size());
  for (size_t i = 0; i < edits.size(); ++i) {
    const SpaceTimeEdit& e = edits[i];
    // A still edit (edit-region before its drag) changes nothing: no region to select or factor.
    if (e.move == Eigen::Vector3d::Zero() && e.rotation.coeffs() == Eigen::Quaterniond::Identity().coeffs()) continue;
    try {
      const ManifoldEditor* editor = nullptr;
      std::unique_ptr<ManifoldEditor> own;
      if (cache) {
        if (cache->entries.size() <= i) cache->entries.resize(i + 1);
        std::unique_ptr<SpaceTimeEditCache::Entry>& c = cache->entries[i];
        // Reused only on the very same vertices: an earlier edit or a key change rebuilds it.
        if (!c || !c->setup.same_setup(e) || c->input.rows() != m.V.rows() || c->input != m.V) {
          c = std::make_unique<SpaceTimeEditCache::Entry>();
          c->editor = make_editor(m, e);  // throws before the entry is usable: left with no editor
          c->setup = e;
          c->input = m.V;
        }
        editor = c->editor.get();
      } else {
        own = make_editor(m, e);
        editor = own.get();
      }
      ManifoldDrag d;
      d.translation = e.move;
      d.rotation = e.rotation.toRotationMatrix();
      if (e.rotation.coeffs() == Eigen::Quaterniond::Identity().coeffs()) d.rotation = Eigen::Matrix3d::Identity();
      m.V = editor->drag(d);
    } catch (const Error& err) {
      if (cache && cache->entries.size() > i) cache->entries[i].reset();
      notes.push_back("space-time edit " + std::to_string(i + 1) + " skipped: " + err.what());
    }
  }
  return notes;
}

Eigen::MatrixXd edited_vertex_normals(const AnimationManifold& m, const Eigen::MatrixXd& base_normals,
                                      const std::vector<SpaceTimeEdit>& edits) {
  Eigen::MatrixXd N = base_normals;
  for (const SpaceTimeEdit& e : edits) {
    int first = -1, last = -1;
    for (int s = 0; s < m.num_slabs(); ++s)
      if (m.times[s + 1] >= e.region.t0 && m.times[s] <= e.region.t1) last = s, first = first < 0 ? s : first;
    if (first < 0) continue;
    const VertexNormalSource src(m, nullptr, m.slab_offsets[first], m.slab_offsets[last + 1]);
    for (int v = 0; v < m.num_vertices(); ++v)
      if (m.V(v, 3) >= e.region.t0 && m.V(v, 3) <= e.region.t1) N.row(v) = src(v).transpose();
  }
  return N;
}

}  // namespace dfm
