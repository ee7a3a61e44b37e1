#pragma once
// A minimal parallel loop over [0, n) on std::threads (chunks handed out dynamically).
#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace dfm {

template <class Body>
void parallel_for(int n, int threads, const Body& body) {
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  threads = std::min(threads, std::max(1, n / 64));
  if (threads <= 1) {
    for (int i = 0; i < n; ++i) body(i);
    return;
  }
  std::atomic<int> next{0};
  const int chunk = 64;
  auto work = [&] {
    for (int s; (s = next.fetch_add(chunk)) < n;)
      for (int i = s, e = std::min(n, s + chunk); i < e; ++i) body(i);
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
}

}  // namespace dfm
