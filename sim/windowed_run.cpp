#include "sim/windowed_run.hpp"

#include <algorithm>

#include "sim/assert.hpp"

namespace masnet::sim {
namespace {
constexpr int kSpins = 500;  // then sleep: docs/performance.md, "Windows on threads"
}  // namespace

void WindowedRun::Barrier::arrive_and_wait() {
  const std::uint32_t phase = phase_.load(std::memory_order_acquire);
  if (arrived_.fetch_add(1, std::memory_order_acq_rel) + 1 == count_) {
    arrived_.store(0, std::memory_order_relaxed);
    phase_.store(phase + 1, std::memory_order_release);
    phase_.notify_all();
    return;
  }
  for (int i = 0; i < kSpins; ++i) {
    if (phase_.load(std::memory_order_acquire) != phase) return;
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  }
  while (phase_.load(std::memory_order_acquire) == phase)
    phase_.wait(phase, std::memory_order_acquire);
}

WindowedRun::WindowedRun(std::vector<Simulator*> parts, Duration lookahead, unsigned threads)
    : parts_(std::move(parts)),
      lookahead_(lookahead),
      threads_(std::clamp<unsigned>(threads, 1,
                                    std::max<unsigned>(static_cast<unsigned>(parts_.size()), 1))),
      start_(threads_),
      done_(threads_) {
  MASNET_ASSERT(lookahead_.count() > 0, "a windowed run needs a positive lookahead");
  for (const Simulator* part : parts_)
    MASNET_ASSERT(part->ties_by_origin(), "the parts of a windowed run use the origin order");
  for (unsigned t = 1; t < threads_; ++t)
    workers_.emplace_back([this, t] { work(t); });
}

WindowedRun::~WindowedRun() {
  stopping_ = true;
  start_.arrive_and_wait();  // the workers see stopping_ and leave
  for (std::thread& worker : workers_)
    worker.join();
}

void WindowedRun::run_share(unsigned thread) {
  // A fixed share per thread: which thread runs a part does not matter, but keeping a part on
  // one thread keeps its data in that core's caches.
  for (std::size_t p = thread; p < parts_.size(); p += threads()) {
    if (prepare_) prepare_(p);
    parts_[p]->run_until(window_end_);
  }
}

void WindowedRun::work(unsigned thread) {
  for (;;) {
    start_.arrive_and_wait();
    if (stopping_) return;
    run_share(thread);
    done_.arrive_and_wait();
  }
}

void WindowedRun::run_until(Time end, const std::function<void(Time window_end)>& exchange,
                            const std::function<Time(Time earliest_here)>& agree) {
  for (;;) {
    Time earliest = kTimeMax;
    for (const Simulator* part : parts_)
      earliest = std::min(earliest, part->next_time());
    if (agree) earliest = agree(earliest);
    if (earliest > end) break;
    // Nothing sent in [earliest, earliest + lookahead) arrives before the window's end.
    window_end_ = std::min(end, earliest + lookahead_ - Duration{1});
    start_.arrive_and_wait();
    run_share(0);
    done_.arrive_and_wait();
    ++windows_;
    exchange(window_end_);
  }
  for (Simulator* part : parts_)
    part->run_until(end);  // nothing is due by then: only the clocks move
}

}  // namespace masnet::sim
