// Replaying a scene's space-time edits onto its manifold (space_time_edit.h): the editor cache, the
// replay and the window's normals. Apart from the edits' own checks, which the scene reader (and its
// fuzz target) links without the solver.
#include "core/scene/space_time_edit.h"

#include <algorithm>
#include <cstring>

#include "core/anim/manifold_normals.h"
#include "core/anim/manifold_refine.h"
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

ManifoldEditOptions edit_options(const SpaceTimeEdit& e) {
  ManifoldEditOptions o;
  o.weights = e.weights;
  o.time_scale = e.time_scale;
  o.preserve_volume = e.preserve_volume;
  return o;
}

std::unique_ptr<ManifoldEditor> make_editor(const AnimationManifold& m, const SpaceTimeEdit& e) {
  return std::make_unique<ManifoldEditor>(m, select_edit_region(m, e.region, e.handle), e.handle.point, edit_options(e));
}

ManifoldDrag edit_drag(const SpaceTimeEdit& e) {
  ManifoldDrag d;
  d.translation = e.move;
  d.rotation = e.rotation.toRotationMatrix();
  if (e.rotation.coeffs() == Eigen::Quaterniond::Identity().coeffs()) d.rotation = Eigen::Matrix3d::Identity();
  d.retime = e.retime;
  return d;
}

// A refined edit: made again on its refined manifold (m unchanged on an error).
void apply_refined(AnimationManifold& m, const SpaceTimeEdit& e) {
  m = edit_refined(m, e.region, e.handle, edit_options(e), edit_drag(e));
}

// The edit's drag onto m (a retime's slabs merged on a copy: a refusal leaves m as it was).
void apply_drag(AnimationManifold& m, const ManifoldEditor& editor, const SpaceTimeEdit& e) {
  const ManifoldDrag d = edit_drag(e);
  if (e.retime != 0) {
    AnimationManifold retimed = m;
    retimed.V = editor.drag(d);
    merge_retimed_slabs(retimed);
    m = std::move(retimed);
  } else {
    editor.drag_onto(d, m.V);  // m.V is the editor's input: only the region's rows change
  }
}

}  // namespace

void apply_space_time_edit(AnimationManifold& m, const SpaceTimeEdit& e) {
  if (e.refine)
    apply_refined(m, e);
  else
    apply_drag(m, *make_editor(m, e), e);
}

SpaceTimeRetimeTrial::SpaceTimeRetimeTrial(AnimationManifold before, const SpaceTimeEdit& e)
    : before_(std::move(before)), edit_(e), editor_(make_editor(before_, e)) {}
SpaceTimeRetimeTrial::~SpaceTimeRetimeTrial() = default;

std::string SpaceTimeRetimeTrial::refusal(double retime) const {
  SpaceTimeEdit e = edit_;
  e.retime = retime;
  AnimationManifold m = before_;
  try {
    if (e.refine)
      apply_refined(m, e);
    else
      apply_drag(m, *editor_, e);  // the replay's own step: what it refuses is refused here
  } catch (const Error& err) {
    return err.what();
  }
  return "";
}

std::vector<std::string> apply_space_time_edits(AnimationManifold& m, const std::vector<SpaceTimeEdit>& edits,
                                                SpaceTimeEditCache* cache) {
  std::vector<std::string> notes;
  if (cache && cache->entries.size() > edits.size()) cache->entries.resize(edits.size());
  if (cache) {
    cache->written.clear();
    cache->written_valid = true;
  }
  for (size_t i = 0; i < edits.size(); ++i) {
    const SpaceTimeEdit& e = edits[i];
    // A still edit (edit-region before its drag) changes nothing: no region to select or factor.
    if (e.move == Eigen::Vector3d::Zero() && e.rotation.coeffs() == Eigen::Quaterniond::Identity().coeffs() &&
        e.retime == 0)
      continue;
    try {
      if (e.refine) {
        // New vertices and prisms: no cached factorisation, and the rows written are all new.
        if (cache && cache->entries.size() > i) cache->entries[i].reset();
        apply_refined(m, e);
        if (cache) cache->written_valid = false;
        continue;
      }
      const ManifoldEditor* editor = nullptr;
      std::unique_ptr<ManifoldEditor> own;
      if (cache) {
        if (cache->entries.size() <= i) cache->entries.resize(i + 1);
        std::unique_ptr<SpaceTimeEditCache::Entry>& c = cache->entries[i];
        // Reused only on the very same vertices: an earlier edit or a key change rebuilds it.
        if (!c || !c->setup.same_setup(e) || c->input.rows() != m.V.rows() ||
            std::memcmp(c->input.data(), m.V.data(), sizeof(double) * m.V.size()) != 0) {  // bits: 4x Eigen's !=
          c = std::make_unique<SpaceTimeEditCache::Entry>();
          cache->plan_rows.clear();  // the normals' plan too: it may be another manifold (new keys)
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
      if (cache) {
        cache->written_valid &= e.retime == 0;
        const std::vector<int>& region = editor->selection().region;
        cache->written.insert(cache->written.end(), region.begin(), region.end());
      }
    } catch (const Error& err) {
      if (cache && cache->entries.size() > i) cache->entries[i].reset();
      notes.push_back("space-time edit " + std::to_string(i + 1) + " skipped: " + err.what());
    }
  }
  if (cache) {
    std::sort(cache->written.begin(), cache->written.end());
    cache->written.erase(std::unique(cache->written.begin(), cache->written.end()), cache->written.end());
  }
  return notes;
}

Eigen::MatrixXd edited_vertex_normals(const AnimationManifold& m, const MatrixX4dRow& base_V,
                                      const Eigen::MatrixXd& base_normals, const std::vector<SpaceTimeEdit>& edits) {
  Eigen::MatrixXd N = base_normals;
  // The tetrahedra of the slabs overlapping any edit's window hold every moved vertex's star and its
  // neighbours' stars (a region vertex's star lies in its window).
  int first = m.num_tets(), last = 0;
  for (const SpaceTimeEdit& e : edits)
    for (int s = 0; s < m.num_slabs(); ++s)
      if (m.times[s + 1] >= e.region.t0 && m.times[s] <= e.region.t1)
        first = std::min(first, m.slab_offsets[s]), last = std::max(last, m.slab_offsets[s + 1]);
  if (base_V.rows() != m.V.rows()) return manifold_vertex_normals(m);  // a refined edit's new vertices
  if (first >= last) return N;
  const int nv = m.num_vertices();
  std::vector<char> moved(nv, 0);
  bool any = false;
  for (int v = 0; v < nv; ++v) any |= moved[v] = m.V.row(v) != base_V.row(v);
  if (!any) return N;
  // Affected: a vertex sharing a tetrahedron with a moved one (its star's normals changed).
  std::vector<int> slot(nv, -1);
  std::vector<int> affected;
  for (int k = first; k < last; ++k) {
    if (!moved[m.T(k, 0)] && !moved[m.T(k, 1)] && !moved[m.T(k, 2)] && !moved[m.T(k, 3)]) continue;
    for (int c = 0; c < 4; ++c)
      if (slot[m.T(k, c)] < 0) slot[m.T(k, c)] = static_cast<int>(affected.size()), affected.push_back(m.T(k, c));
  }
  // Their stars, in increasing tetrahedron order like manifold_vertex_normals: the same bits.
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(affected.size(), 8);
  for (int k = first; k < last; ++k) {
    if (slot[m.T(k, 0)] < 0 && slot[m.T(k, 1)] < 0 && slot[m.T(k, 2)] < 0 && slot[m.T(k, 3)] < 0) continue;
    const Eigen::RowVector4d n = tet_normal4(m, k).transpose();
    for (int c = 0; c < 4; ++c)
      if (slot[m.T(k, c)] >= 0) add_tet_normal(m, k, c, n, sum, slot[m.T(k, c)]);
  }
  for (size_t a = 0; a < affected.size(); ++a) N.row(affected[a]) = vertex_normal4(sum.row(a)).transpose();
  return N;
}

void edited_vertex_normals(const AnimationManifold& m, const MatrixX4dRow& base_V, const Eigen::MatrixXd& base_normals,
                           const std::vector<SpaceTimeEdit>& edits, SpaceTimeEditCache& cache, Eigen::MatrixXd& N) {
  if (!cache.written_valid || base_V.rows() != m.V.rows() || base_normals.rows() != m.V.rows()) {
    N = edited_vertex_normals(m, base_V, base_normals, edits);
    return;
  }
  N = base_normals;
  if (cache.written.empty()) return;
  const int nv = m.num_vertices();
  if (cache.plan_rows != cache.written) {
    // Affected: a vertex sharing a tetrahedron with a written row; its whole star is summed again.
    std::vector<char> written(nv, 0);
    for (int v : cache.written) written[v] = 1;
    std::vector<int> slot(nv, -1);
    cache.plan_affected.clear();
    for (int k = 0; k < m.num_tets(); ++k) {
      if (!written[m.T(k, 0)] && !written[m.T(k, 1)] && !written[m.T(k, 2)] && !written[m.T(k, 3)]) continue;
      for (int c = 0; c < 4; ++c)
        if (slot[m.T(k, c)] < 0) slot[m.T(k, c)] = static_cast<int>(cache.plan_affected.size()), cache.plan_affected.push_back(m.T(k, c));
    }
    cache.plan_tets.clear();
    cache.plan_slots.clear();
    cache.plan_sums.clear();
    cache.plan_moves.clear();
    cache.plan_normals.clear();
    for (int k = 0; k < m.num_tets(); ++k) {
      const std::array<int, 4> s{slot[m.T(k, 0)], slot[m.T(k, 1)], slot[m.T(k, 2)], slot[m.T(k, 3)]};
      if (s[0] < 0 && s[1] < 0 && s[2] < 0 && s[3] < 0) continue;
      cache.plan_tets.push_back(k);
      cache.plan_slots.push_back(s);
      std::array<int, 4> sums{};
      for (int c = 0; c < 4; ++c) sums[c] = tet_normal_sums(m, k, c);  // t does not change without a retime
      cache.plan_sums.push_back(sums);
      const bool moves = written[m.T(k, 0)] || written[m.T(k, 1)] || written[m.T(k, 2)] || written[m.T(k, 3)];
      cache.plan_moves.push_back(moves);
      cache.plan_normals.push_back(moves ? Eigen::RowVector4d::Zero() : Eigen::RowVector4d(tet_normal4(m, k).transpose()));
    }
    cache.plan_rows = cache.written;
  }
  // Each affected vertex's star in increasing tetrahedron order, like manifold_vertex_normals: the
  // same bits (an affected vertex whose star did not move gets its base normal again).
  Eigen::Matrix<double, Eigen::Dynamic, 8, Eigen::RowMajor> sum = decltype(sum)::Zero(cache.plan_affected.size(), 8);
  for (size_t i = 0; i < cache.plan_tets.size(); ++i) {
    const Eigen::RowVector4d n =
        cache.plan_moves[i] ? Eigen::RowVector4d(tet_normal4(m, cache.plan_tets[i]).transpose()) : cache.plan_normals[i];
    for (int c = 0; c < 4; ++c) {
      const int a = cache.plan_slots[i][c];
      if (a < 0) continue;
      if (cache.plan_sums[i][c] & 1) sum.row(a).head<4>() += n;
      if (cache.plan_sums[i][c] & 2) sum.row(a).tail<4>() += n;
    }
  }
  for (size_t a = 0; a < cache.plan_affected.size(); ++a) N.row(cache.plan_affected[a]) = vertex_normal4(sum.row(a)).transpose();
}

}  // namespace dfm
