#pragma once
// parallel_for(n, jobs, fn): calls fn(i) for every i in [0, n) on up to `jobs` threads, each
// thread taking the next unclaimed index. Results are deterministic as long as fn(i) writes
// only to slot i (the order in which indices run is not). On one thread the indices run in
// order on the calling thread and an exception stops them; on several, the first exception
// thrown by any fn(i) is rethrown after every thread has finished (the other indices still run).
// `poll`, when given, is called on the calling thread about every `poll_period` while the
// indices run (e.g. to show progress), and once more at the end.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace shudder {

template <class Fn>
void parallel_for(std::size_t n, unsigned jobs, Fn&& fn, const std::function<void()>& poll = {},
                  std::chrono::milliseconds poll_period = std::chrono::milliseconds(200)) {
  const unsigned threads = std::max(1u, std::min<unsigned>(jobs, static_cast<unsigned>(n)));
  std::exception_ptr error;
  std::mutex error_mutex;
  const auto run = [&](std::size_t i) {
    try {
      fn(i);
    } catch (...) {
      const std::lock_guard lock(error_mutex);
      if (!error) error = std::current_exception();
    }
  };
  if (threads <= 1 && !poll) {
    for (std::size_t i = 0; i < n; ++i) fn(i);
    return;
  }
  {
    std::atomic<std::size_t> next{0}, done{0};
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t)
      pool.emplace_back([&] {
        for (std::size_t i; (i = next++) < n;) {
          run(i);
          ++done;
        }
      });
    while (poll && done < n) {
      poll();
      std::this_thread::sleep_for(poll_period);
    }
    for (auto& th : pool) th.join();
    if (poll) poll();
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace shudder
