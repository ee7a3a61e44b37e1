#pragma once
// The document's space-time edits (issue 35; Southern 2008 ch. 4): drags of the animation manifold
// itself, stored in the scene and replayed in order onto the manifold built from the keys, so the
// viewport, save-posed and save-frames all see them. Each edit is a region (a ball over a time
// window), a handle (a point at a time) and its move (core/anim/manifold_edit.h).
#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/anim/manifold.h"
#include "core/anim/manifold_edit.h"
#include "core/anim/manifold_edit_region.h"

namespace dfm {

struct SpaceTimeEdit {
  EditRegionSpec region;
  EditHandleSpec handle;
  Eigen::Vector3d move = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  // about the handle point
  double retime = 0;  // the handle's move in t (ManifoldDrag::retime; scenes before it have none: 0)
  LaplacianWeights weights = LaplacianWeights::Reciprocal;
  double time_scale = 1.0;
  bool preserve_volume = false;
  // Refine what the edit stretches (manifold_refine.h, Southern 4.5.1): the replay makes the edit with
  // edit_refined, whose layers have more vertices (scenes before it have none: false).
  bool refine = false;
  bool operator==(const SpaceTimeEdit& o) const;
  // Everything but the move, rotation, retime and refinement: edits with the same setup share one
  // factorisation (a refined edit is factored on its refined manifold, without the cache).
  bool same_setup(const SpaceTimeEdit& o) const;
};

// Checks the numbers (finite, radius > 0, t0 < t1, handle time in the window, unit rotation, time
// scale > 0); throws dfm::Error saying what is wrong.
void check_space_time_edit(const SpaceTimeEdit& e);

// ManifoldEditors kept between replays: a drag that changes only an edit's move is not factored again
// (4.6.1): a translation moves the region by its reach, a turn is a back substitution. Each replay
// writes only the regions' rows. Not part of the document.
class SpaceTimeEditCache {
 public:
  SpaceTimeEditCache();
  ~SpaceTimeEditCache();
  struct Entry;
  std::vector<std::unique_ptr<Entry>> entries;  // one per edit, in order
  // The rows the last apply_space_time_edits wrote (sorted); every other row is as it was given.
  // Not valid after a retime (its slabs are merged: new rows).
  std::vector<int> written;
  bool written_valid = false;
  // edited_vertex_normals' plan for the rows plan_rows: plan_affected, the vertices sharing a
  // tetrahedron with one of them; plan_tets, their stars' tetrahedra in increasing order, with each
  // corner's index in plan_affected (-1: not affected) in plan_slots and its tet_normal_sums in
  // plan_sums; plan_moves, whether the tetrahedron has a plan row (else plan_normals holds its tet_normal4).
  std::vector<int> plan_rows, plan_affected, plan_tets;
  std::vector<std::array<int, 4>> plan_slots, plan_sums;
  std::vector<char> plan_moves;
  std::vector<Eigen::RowVector4d> plan_normals;
};

// Applies `edits` in order to m.V. An edit whose region no longer selects anything (the keys changed:
// it is stale) is skipped and named in the returned notes ("space-time edit 2 skipped: ..."); the
// others still apply. An edit with no move, turn or retime is skipped (it changes nothing). `cache` may be null.
std::vector<std::string> apply_space_time_edits(AnimationManifold& m, const std::vector<SpaceTimeEdit>& edits,
                                                SpaceTimeEditCache* cache = nullptr);

// One edit onto m, without a cache; throws dfm::Error (m unchanged) where the replay would skip it.
void apply_space_time_edit(AnimationManifold& m, const SpaceTimeEdit& e);

// One edit's replay factored once, to try retimes on: the editor's retime drag asks every frame whether
// the replay would take the value (a refused one left in the document would make the replay skip the
// whole edit, its move too). The constructor throws dfm::Error where the edit cannot be made on
// `before` (the manifold before it: manifold_before_edit) at all.
class SpaceTimeRetimeTrial {
 public:
  SpaceTimeRetimeTrial(AnimationManifold before, const SpaceTimeEdit& e);
  ~SpaceTimeRetimeTrial();
  // "" when the edit with this retime applies, else why the replay would skip it (a slab folding back
  // in time, the first or last layer in the region).
  std::string refusal(double retime) const;

 private:
  AnimationManifold before_;
  SpaceTimeEdit edit_;
  std::unique_ptr<ManifoldEditor> editor_;
};

// manifold_vertex_normals(edited), bit for bit, from the unedited manifold's vertices and normals:
// only the rows of vertices sharing a tetrahedron with a moved vertex (base_V row != edited row) are
// summed again, over their stars (found in the slabs overlapping the edits' windows). What a drag
// frame's view needs without a full pass.
Eigen::MatrixXd edited_vertex_normals(const AnimationManifold& edited, const MatrixX4dRow& base_V,
                                      const Eigen::MatrixXd& base_normals, const std::vector<SpaceTimeEdit>& edits);
// The same into N (its storage reused), for `edited` = base_V's manifold after
// apply_space_time_edits(edited, edits, &cache): only the stars around the rows the replay wrote are
// summed again, found once per set of regions instead of per frame (a drag frame's normals). Falls back
// to the call above after a retime.
void edited_vertex_normals(const AnimationManifold& edited, const MatrixX4dRow& base_V,
                           const Eigen::MatrixXd& base_normals, const std::vector<SpaceTimeEdit>& edits,
                           SpaceTimeEditCache& cache, Eigen::MatrixXd& N);

}  // namespace dfm
