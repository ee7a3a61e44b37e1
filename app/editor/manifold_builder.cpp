#include "app/editor/manifold_builder.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>

#include "core/anim/manifold_normals.h"
#include "core/anim/manifold_sequence.h"
#include "core/anim/transition.h"
#include "core/scene/key_surfaces.h"
#include "core/util/error.h"
#include "core/util/hash.h"

namespace dfm::editor {

namespace {
template <class M>
std::uint64_t mix_matrix(std::uint64_t h, const M& m) {
  const Eigen::Index r = m.rows(), c = m.cols();
  h = fnv1a(h, &r, sizeof r);
  h = fnv1a(h, &c, sizeof c);
  return fnv1a(h, m.data(), sizeof(typename M::Scalar) * m.size());
}
}  // namespace

std::uint64_t manifold_signature(const Document& doc) {
  const auto& keys = doc.keys();
  if (keys.size() < 2) return 0;
  bool pose_keys = false;
  for (const SceneKey& k : keys) pose_keys |= !k.is_mesh();
  if (pose_keys && (!doc.has_weights() || doc.surface().num_vertices() == 0)) return 0;
  std::uint64_t h = kFnv1aBasis;
  for (size_t i = 0; i < keys.size(); ++i) {
    h = fnv1a(h, &keys[i].time, sizeof(double));
    h = fnv1a(h, &keys[i].inbetween, sizeof(InbetweenMethod));
    h = mix_matrix(h, keys[i].pairs_to_next);
    h = mix_matrix(h, keys[i].transition_to_next);  // a local transition's in-betweens (key_surfaces)
    if (keys[i].is_mesh()) {
      h = fnv1a(h, "mesh", 4);
      h = mix_matrix(h, keys[i].mesh.V);
      h = mix_matrix(h, keys[i].mesh.F);
    } else {
      for (const auto& T : doc.skin_pose(keys[i].params).transforms)  // with the additional handles'
        h = fnv1a(h, T.matrix().data(), sizeof(double) * 16);
      for (const BoneTwistStretch& ts : keys[i].params.bone_twist_stretch)  // STBS reads the start twist too
        h = fnv1a(h, &ts.twist_start, sizeof(double));
    }
  }
  const int ib = doc.inbetweens();  // arap / linear intervals between mesh keys use it too
  h = fnv1a(h, &ib, sizeof ib);
  if (pose_keys) {
    const int m = static_cast<int>(doc.method()), k = doc.bind_settings().max_influences;
    h = fnv1a(h, &m, sizeof m);
    h = fnv1a(h, &k, sizeof k);
    // Not the data's address: a re-bind assigns same-size weights into the same storage.
    const std::uint64_t sw = doc.surface_weights_revision();
    h = fnv1a(h, &sw, sizeof sw);
    for (const EndpointFilter& f : doc.endpoint_filters()) {
      const size_t n = f.size();
      h = fnv1a(h, &n, sizeof n);
      for (const Eigen::Vector2d& p : f) h = fnv1a(h, p.data(), sizeof(double) * 2);
    }
  }
  return h == 0 ? 1 : h;
}

// One background build: its own copy of the key surfaces; the result is read after `done`.
struct ManifoldBuilder::Job {
  std::thread thread;
  std::uint64_t sig = 0;
  std::vector<KeySurface> keys;
  KeyTrack track;
  std::atomic<bool> cancel{false}, done{false};
  std::atomic<int> slabs_done{0}, slabs_total{0};
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
  AnimationManifold result;
  std::string error;
  bool ok = false;
};

ManifoldBuilder::ManifoldBuilder() : cache_(std::make_unique<SpaceTimeEditCache>()) {}

ManifoldBuilder::~ManifoldBuilder() {
  if (job_) {
    job_->cancel = true;
    if (job_->thread.joinable()) job_->thread.join();
  }
}

void ManifoldBuilder::collect() {
  if (!job_ || !job_->done.load(std::memory_order_acquire)) return;
  std::shared_ptr<Job> j = std::move(job_);
  job_.reset();
  if (j->thread.joinable()) j->thread.join();
  // Stale (finished after an edit, or cancelled): the newer keys build next.
  if (j->sig != wanted_sig_ || (!j->ok && j->cancel.load())) return;
  built_sig_ = j->sig;
  if (j->ok) {
    base_ = std::make_shared<const AnimationManifold>(std::move(j->result));
    ++base_serial_;
    track_ = std::move(j->track);
    has_ = true;
    error_.clear();
  } else {
    has_ = false;
    error_ = "animation manifold: " + j->error;
  }
}

void ManifoldBuilder::start(const Document& doc) {
  built_sig_ = wanted_sig_;  // a failure below is not retried until the keys change
  has_ = false;
  std::vector<KeySurface> keys;
  try {
    keys = key_surfaces(doc);
  } catch (const std::exception& e) {
    error_ = std::string("animation manifold: ") + e.what();
    return;
  }
  KeyTrack track = doc.has_mesh_keys() ? KeyTrack{} : pose_key_track(doc);
  placements_.clear();
  for (size_t i = 0; i + 1 < keys.size(); ++i)
    if (!same_connectivity(keys[i], keys[i + 1]))
      placements_.emplace_back(keys[i].time, transition_placement(TriMesh{keys[i].V, keys[i].F, {}}, TriMesh{keys[i + 1].V, keys[i + 1].F, {}}));
  if (placements_.empty()) {  // no transition (needs_transition's rule, read off the loop above)
    // The prism build only: milliseconds, as before mesh keys existed.
    try {
      base_ = std::make_shared<const AnimationManifold>(build_manifold_sequence(keys));
      ++base_serial_;
      track_ = std::move(track);
      has_ = true;
      error_.clear();
    } catch (const std::exception& e) {
      error_ = std::string("animation manifold: ") + e.what();
    }
    return;
  }
  built_sig_ = 0;  // not built until the job is collected
  auto j = std::make_shared<Job>();
  j->sig = wanted_sig_;
  j->keys = std::move(keys);
  j->track = std::move(track);
  j->slabs_total = static_cast<int>(j->keys.size()) - 1;
  Job* raw = j.get();
  j->thread = std::thread([raw] {
    // The UI thread must keep the CPU (as the bind worker does): a lower priority for this thread.
    setpriority(PRIO_PROCESS, static_cast<id_t>(::syscall(SYS_gettid)), 10);
    try {
      raw->result = build_manifold_sequence(raw->keys, TransitionOptions{}, nullptr, [raw](int done, int total) {
        raw->slabs_done = done;
        raw->slabs_total = total;
        return !raw->cancel.load();
      });
      raw->ok = true;
    } catch (const std::exception& e) {
      raw->error = raw->cancel.load() ? "cancelled" : e.what();
    }
    raw->done.store(true, std::memory_order_release);
  });
  job_ = std::move(j);
}

const KeyPlacement* ManifoldBuilder::transition_placement_from(double t0) const {
  for (const auto& [time, p] : placements_)
    if (time == t0) return &p;
  return nullptr;
}

bool ManifoldBuilder::update(const Document& doc) {
  const std::uint64_t before = built_sig_;
  const bool had = has_;
  collect();
  if (doc.revision() != seen_revision_) {
    seen_revision_ = doc.revision();
    wanted_sig_ = manifold_signature(doc);
  }
  if (wanted_sig_ == 0) {
    has_ = false;
    built_sig_ = 0;
    error_.clear();
    if (job_) job_->cancel = true;
    return false;
  }
  if (wanted_sig_ != built_sig_) {
    if (job_) {
      job_->cancel = job_->sig != wanted_sig_;  // a stale one is collected (and dropped) when it stops
    } else {
      start(doc);
    }
  }
  const bool replayed = replay(doc);
  if (!replayed) positions_only_ = false;
  return has_ && (built_sig_ != before || !had || replayed);
}

bool ManifoldBuilder::replay(const Document& doc) {
  if (!has_) return false;
  const std::vector<SpaceTimeEdit>& edits = doc.space_time_edits();
  if (replayed_serial_ == base_serial_ && edits == applied_) return false;
  const auto t0 = std::chrono::steady_clock::now();
  if (replayed_serial_ != base_serial_)
    base_normals_ = std::make_shared<const Eigen::MatrixXd>(manifold_vertex_normals(*base_));
  const std::uint64_t shown_before = shown_topology_;
  if (edits.empty()) {
    manifold_ = base_;
    normals_ = base_normals_;
    edit_notes_.clear();
    shown_topology_ = base_serial_;
  } else {
    // The pair nobody else holds (the view and its prefetch worker may still read the other one);
    // after seeing a count of 1 nobody can take a new reference, the fence orders their last reads.
    Edited* e = nullptr;
    for (Edited& c : edited_)
      if (c.manifold.use_count() <= 1 && c.normals.use_count() <= 1) e = &c;
    if (!e) e = edited_[0].manifold == manifold_ ? &edited_[1] : &edited_[0];
    std::atomic_thread_fence(std::memory_order_acquire);
    if (e->manifold.use_count() == 1 && e->base_serial == base_serial_) {
      e->manifold->V = base_->V;
    } else {
      e->manifold = std::make_shared<AnimationManifold>(*base_);
    }
    if (e->normals.use_count() != 1) e->normals = std::make_shared<Eigen::MatrixXd>();
    e->base_serial = ~0ull;  // until the replay says which rows it wrote
    edit_notes_ = apply_space_time_edits(*e->manifold, edits, cache_.get());
    e->base_serial = cache_->written_valid ? base_serial_ : ~0ull;
    edited_vertex_normals(*e->manifold, base_->V, *base_normals_, edits, *cache_, *e->normals);
    manifold_ = e->manifold;
    normals_ = e->normals;
    shown_topology_ = e->base_serial;
  }
  positions_only_ = shown_topology_ != ~0ull && shown_topology_ == shown_before;
  applied_ = edits;
  replayed_serial_ = base_serial_;
  replay_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return true;
}

std::string ManifoldBuilder::progress_text() const {
  if (!job_) return "";
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - job_->started).count();
  char buf[160];
  if (job_->cancel.load())
    std::snprintf(buf, sizeof buf, "animation manifold: stopping an outdated build (%.1f s)", s);
  else
    std::snprintf(buf, sizeof buf, "building the animation manifold (transition): slab %d of %d done, %.1f s",
                  job_->slabs_done.load(), job_->slabs_total.load(), s);
  return buf;
}

}  // namespace dfm::editor
