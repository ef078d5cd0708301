// mosb's one thread pool: indices handed out in ascending order by an atomic counter to up to N
// threads, the caller's thread one of them, and the failure a sequential loop would have met
// rethrown once every thread has stopped.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace mosb {

// `asked` threads, or when it is 0 as many as the hardware runs at once (at least 1).
inline unsigned thread_count(unsigned asked) {
  return asked != 0 ? asked : std::max(1U, std::thread::hardware_concurrency());
}

// Runs body(state, i) for every i in [0, count) on at most `threads` threads (0 counts as 1):
// worker 0 is the caller's thread, workers 1 and up are started here. A worker that takes an index
// first makes its state, on its own thread, by make_state(worker) (a workspace, a connection, a
// process runner), passes it to every body it runs, and destroys it on that thread when it stops.
//
// After a body (or make_state) throws, no worker takes another index; the ones taken run to their
// end. Once every worker has stopped, the exception of the lowest index that threw is rethrown.
// Indices are taken in order, so every index below one that threw has been taken and has run:
// that exception is the one a sequential loop over independent bodies would throw.
template <class MakeState, class Body>
void parallel_for_with_state(std::size_t count, unsigned threads, MakeState&& make_state,
                             Body&& body) {
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex failure_mutex;
  std::size_t failed_index = count;
  std::exception_ptr failure;
  const auto take = [&] { return failed.load() ? count : next.fetch_add(1); };
  const auto worker = [&](unsigned index) {
    std::size_t i = take();
    if (i >= count) return;
    try {
      auto state = make_state(index);
      for (; i < count; i = take()) body(state, i);
    } catch (...) {
      const std::lock_guard lock(failure_mutex);
      if (i < failed_index) {
        failed_index = i;
        failure = std::current_exception();
      }
      failed.store(true);
    }
  };
  {
    const auto workers = static_cast<unsigned>(std::min<std::size_t>(std::max(threads, 1U), count));
    std::vector<std::jthread> pool;
    pool.reserve(workers > 0 ? workers - 1 : 0);
    for (unsigned w = 1; w < workers; ++w) pool.emplace_back(worker, w);
    worker(0);
  }  // joins the pool
  if (failure) std::rethrow_exception(failure);
}

// Runs body(i) for every i in [0, count) on at most `threads` threads, as parallel_for_with_state
// does (the caller's thread one of them; the exception of the lowest index that threw rethrown).
template <class Body>
void parallel_for(std::size_t count, unsigned threads, Body&& body) {
  struct NoState {};
  parallel_for_with_state(
      count, threads, [](unsigned) { return NoState{}; },
      [&body](NoState&, std::size_t i) { body(i); });
}

}  // namespace mosb
