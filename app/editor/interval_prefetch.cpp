#include "app/editor/interval_prefetch.h"

#include <chrono>
#include <exception>
#include <utility>

namespace dfm::editor {

IntervalPrefetch::~IntervalPrefetch() { wait(); }

void IntervalPrefetch::wait() {
  if (job_.valid()) job_.wait();
}

void IntervalPrefetch::reset(std::shared_ptr<const AnimationManifold> manifold,
                             std::shared_ptr<const Eigen::MatrixXd> normals4, std::vector<double> times) {
  wait();
  job_ = {};
  interval_ = -1;
  manifold_ = std::move(manifold);
  normals4_ = std::move(normals4);
  times_ = std::move(times);
}

void IntervalPrefetch::request(int i) {
  if (!manifold_ || !normals4_ || i < 0 || i + 1 >= static_cast<int>(times_.size()) || i == interval_) return;
  if (job_.valid() && job_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return;  // busy
  interval_ = i;
  job_ = std::async(std::launch::async, [m = manifold_, n = normals4_, lo = times_[i], hi = times_[i + 1]]()
                                            -> std::optional<PreparedInterval> {
    try {
      PreparedInterval p{build_interval_slice(*m, *n, lo, hi), {}};
      p.records = gl::interval_records(p.topology, *m, *n);
      return p;
    } catch (const std::exception&) {
      return std::nullopt;
    }
  });
}

std::optional<PreparedInterval> IntervalPrefetch::take(int i) {
  if (i != interval_ || !job_.valid()) return std::nullopt;
  interval_ = -1;
  return job_.get();
}

}  // namespace dfm::editor
