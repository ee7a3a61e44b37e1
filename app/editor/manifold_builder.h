#pragma once
// The animation manifold the viewport slices, kept up to date with the document's keys (the same
// core call as the script and the saves: key_surfaces + build_manifold_sequence). Keys that share one
// triangle list build at once on the UI thread (the prism build takes milliseconds); a sequence with a
// transition (a mesh key of another connectivity: seconds) builds on a worker thread at a lower
// priority while the window keeps drawing, with progress text. An edit during a build cancels it
// (between slabs) and the newer keys build next. The document's space-time edits are replayed onto the
// built manifold (core/scene/space_time_edit.h) with their factorisations cached: a drag that changes
// only an edit's move rewrites the regions' rows, not a rebuild.
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/anim/key_alignment.h"
#include "core/anim/keyframes.h"
#include "core/anim/manifold.h"
#include "core/scene/document.h"
#include "core/scene/space_time_edit.h"

namespace dfm::editor {

// What the manifold is made of: key times, poses and meshes, method, in-betweens, weights identity.
// 0 when the document has no manifold to build (fewer than two keys, or pose keys and no weights).
std::uint64_t manifold_signature(const Document& doc);

class ManifoldBuilder {
 public:
  ManifoldBuilder();
  ~ManifoldBuilder();  // cancels a running build and waits for its current slab
  ManifoldBuilder(const ManifoldBuilder&) = delete;
  ManifoldBuilder& operator=(const ManifoldBuilder&) = delete;

  // Cheap when nothing changed; call on every document change and every frame while busy().
  // Returns true when manifold() is new (upload it).
  bool update(const Document& doc);
  // manifold()'s 4D vertex normals (manifold_vertex_normals' bits; after an edit only its window's
  // vertices are recomputed).
  std::shared_ptr<const Eigen::MatrixXd> normals() const { return normals_; }
  // The space-time edits the replay skipped (stale: their region is empty now), one line each.
  const std::vector<std::string>& edit_notes() const { return edit_notes_; }
  // Milliseconds the last replay of the edits took (the regions' rows and their normals, or a
  // factorisation).
  double replay_ms() const { return replay_ms_; }
  // The last new manifold() differs from the one before it in x, y, z only (a drag frame without a
  // retime): the same tetrahedra, times and t, so every interval is cut as before.
  bool positions_only() const { return positions_only_; }
  // The manifold matches the document's keys (false while a build runs or after one failed).
  bool has_manifold() const { return has_; }
  const AnimationManifold& manifold() const { return *manifold_; }
  // The same, shared: a worker may keep reading it after a newer manifold replaces it.
  std::shared_ptr<const AnimationManifold> shared_manifold() const { return manifold_; }
  // The pose keys the manifold was built from when every key is a pose key (the handles follow the
  // animation); empty with mesh keys.
  const KeyTrack& track() const { return track_; }
  // The placement of the transition from the key at time t0 to the next (transition_placement of the
  // key surfaces the manifold is built from), null where no transition starts at t0.
  const KeyPlacement* transition_placement_from(double t0) const;
  // A background build is running, or its result waits for update() to collect it.
  bool busy() const { return job_ != nullptr; }
  // "building animation manifold: transition, slab 1 of 2, 3.4 s" while busy(), else "".
  std::string progress_text() const;
  // Why the last build failed ("" when it did not), e.g. a bad key or a failed transition.
  const std::string& error() const { return error_; }

 private:
  struct Job;
  void collect();
  void start(const Document& doc);
  bool replay(const Document& doc);  // the edits onto base_ -> manifold_; true when manifold_ is new

  std::shared_ptr<Job> job_;
  std::vector<std::pair<double, KeyPlacement>> placements_;  // per transition: its first key's time
  std::shared_ptr<const AnimationManifold> manifold_ = std::make_shared<const AnimationManifold>();
  std::shared_ptr<const AnimationManifold> base_;  // as built from the keys, before the edits
  std::shared_ptr<const Eigen::MatrixXd> base_normals_, normals_;
  std::uint64_t base_serial_ = 0, replayed_serial_ = ~0ull;
  std::vector<SpaceTimeEdit> applied_;
  std::unique_ptr<SpaceTimeEditCache> cache_;
  // Two edited manifolds and normals in turn: a drag frame rewrites the pair the view has let go of
  // (V copied from base_ into its storage when it has base_'s tetrahedra) instead of copying base_.
  struct Edited {
    std::shared_ptr<AnimationManifold> manifold;
    std::shared_ptr<Eigen::MatrixXd> normals;
    std::uint64_t base_serial = ~0ull;  // has base_'s tetrahedra and times when base_serial_ (no retime)
  };
  Edited edited_[2];
  std::uint64_t shown_topology_ = ~0ull;  // manifold_'s tetrahedra and times: a base serial, or ~0 (its own)
  bool positions_only_ = false;
  std::vector<std::string> edit_notes_;
  double replay_ms_ = 0;
  KeyTrack track_;
  bool has_ = false;
  std::string error_;
  std::uint64_t seen_revision_ = ~0ull;
  std::uint64_t wanted_sig_ = 0, built_sig_ = 0;
};

}  // namespace dfm::editor
