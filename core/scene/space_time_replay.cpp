// Replaying a scene's space-time edits onto its manifold (space_time_edit.h): the editor cache, the
// replay and the window's normals. Apart from the edits' own checks, which the scene reader (and its
// fuzz target) links without the solver.
#include "core/scene/space_time_edit.h"

#include "core/anim/manifold_normals.h"
#include "core/anim/manifold_retime.h"
#include "core/util/error.h"

namespace dfm {

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

// The edit's drag onto m (a retime's slabs merged on a copy: a refusal leaves m as it was).
void apply_drag(AnimationManifold& m, const ManifoldEditor& editor, const SpaceTimeEdit& e) {
  ManifoldDrag d;
  d.translation = e.move;
  d.rotation = e.rotation.toRotationMatrix();
  if (e.rotation.coeffs() == Eigen::Quaterniond::Identity().coeffs()) d.rotation = Eigen::Matrix3d::Identity();
  d.retime = e.retime;
  MatrixX4dRow V = editor.drag(d);
  if (e.retime != 0) {
    AnimationManifold retimed = m;
    retimed.V = std::move(V);
    merge_retimed_slabs(retimed);
    m = std::move(retimed);
  } else {
    m.V = std::move(V);
  }
}

}  // namespace

void apply_space_time_edit(AnimationManifold& m, const SpaceTimeEdit& e) { apply_drag(m, *make_editor(m, e), e); }

std::vector<std::string> apply_space_time_edits(AnimationManifold& m, const std::vector<SpaceTimeEdit>& edits,
                                                SpaceTimeEditCache* cache) {
  std::vector<std::string> notes;
  if (cache && cache->entries.size() > edits.size()) cache->entries.resize(edits.size());
  for (size_t i = 0; i < edits.size(); ++i) {
    const SpaceTimeEdit& e = edits[i];
    // A still edit (edit-region before its drag) changes nothing: no region to select or factor.
    if (e.move == Eigen::Vector3d::Zero() && e.rotation.coeffs() == Eigen::Quaterniond::Identity().coeffs() &&
        e.retime == 0)
      continue;
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
      apply_drag(m, *editor, e);
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
