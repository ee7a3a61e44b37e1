#pragma once
// Playback's next interval topology, built ahead on a worker thread (issue 16): while one interval of
// the animation manifold plays from the cache, the one it reaches next is extracted
// (build_interval_slice, core/anim/interval_slice.h) with its GPU records (render/interval_records.h)
// off the UI thread, so crossing a vertex time only copies ready buffers instead of slicing the whole
// manifold within a frame. One build at a time; the manifold and its normals are shared, so a newer
// manifold can replace them meanwhile. No GL.
#include <future>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "core/anim/interval_slice.h"
#include "core/anim/manifold.h"
#include "render/interval_records.h"

namespace dfm::editor {

struct PreparedInterval {
  IntervalSlice topology;
  gl::IntervalRecords records;
};

class IntervalPrefetch {
 public:
  IntervalPrefetch() = default;
  ~IntervalPrefetch();  // waits for a build in flight
  IntervalPrefetch(const IntervalPrefetch&) = delete;
  IntervalPrefetch& operator=(const IntervalPrefetch&) = delete;

  // A new manifold (times: its manifold_vertex_times): waits for a build in flight and drops it.
  void reset(std::shared_ptr<const AnimationManifold> manifold, std::shared_ptr<const Eigen::MatrixXd> normals4,
             std::vector<double> times);
  // Starts building interval i, (times[i], times[i + 1]), unless a build is in flight or i is the
  // interval already built or building (a ready topology of another interval is dropped).
  void request(int i);
  // Interval i's topology: the finished build, or the one in flight (waiting for it). nullopt when
  // neither is i, or when the build failed (the caller's own build reports why).
  std::optional<PreparedInterval> take(int i);
  // The interval built or building, -1 when none.
  int interval() const { return interval_; }

 private:
  void wait();

  std::shared_ptr<const AnimationManifold> manifold_;
  std::shared_ptr<const Eigen::MatrixXd> normals4_;
  std::vector<double> times_;
  int interval_ = -1;
  std::future<std::optional<PreparedInterval>> job_;
};

}  // namespace dfm::editor
