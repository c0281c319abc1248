#pragma once
// The parts of a partitioned run, run side by side in conservative windows
// (docs/decisions/0012-partitioned-runs.md). Every part is a Simulator in the origin order that
// owns some nodes; nothing a part does inside a window [t, t + lookahead) can reach another part
// before the window ends, because every message between parts takes at least the lookahead. So
// each part runs its window alone — on a pool of threads — and then, on the calling thread, the
// caller's exchange moves what crossed (messages with the keys their senders made) into the
// parts they are for. Parts are independent within a window and merge by (time, key): the
// result cannot depend on how many threads ran them.
#include <atomic>
#include <cstdint>
#include <functional>
#include <thread>
#include <vector>

#include "sim/simulator.hpp"

namespace masnet::sim {

class WindowedRun {
 public:
  /// `parts`: the simulators, each in the origin order (asserted); `lookahead` > 0: the least
  /// delay of a message between parts; `threads`: how many threads run the windows (the
  /// calling one included), at least 1 and at most one per part — never more than
  /// allowed_cpu_count() (two threads on one core cost 29 µs a window in their waits).
  WindowedRun(std::vector<Simulator*> parts, Duration lookahead, unsigned threads);
  ~WindowedRun();
  WindowedRun(const WindowedRun&) = delete;
  WindowedRun& operator=(const WindowedRun&) = delete;

  /// Runs every part to `end` (each part's clock ends at `end`). After each window, which
  /// ends at `window_end`, calls `exchange(window_end)`; what it schedules into the parts must
  /// be later than `window_end`. A window starts at the earliest pending event of any part, so
  /// stretches with nothing to do cost nothing.
  /// `agree`, when given, turns this process's earliest pending time into the earliest of every
  /// process running parts of the same run (a minimum over MPI ranks, ranks/rank_exchange.hpp):
  /// all of them then run the same windows.
  void run_until(Time end, const std::function<void(Time window_end)>& exchange,
                 const std::function<Time(Time earliest_here)>& agree = {});

  /// `prepare(part)` runs on the thread that runs `part`, before each of its windows: work the
  /// exchange handed over that each part can do alone (taking in the messages for it) is then
  /// done side by side instead of on the calling thread.
  void set_prepare(std::function<void(std::size_t part)> prepare) { prepare_ = std::move(prepare); }

  std::uint64_t windows() const { return windows_; }
  unsigned threads() const { return threads_; }

 private:
  void run_share(unsigned thread);  // the parts thread, thread + threads(), ... to window_end_
  void work(unsigned thread);       // a worker's loop

  // Every thread waits here until all have arrived: spinning a little first (a window may take
  // microseconds; std::barrier, which sleeps at once, cost 7 µs a window on two cores against
  // 0.35 µs), then sleeping, so that a busy machine is not spun on for long.
  class Barrier {
   public:
    explicit Barrier(std::uint32_t count) : count_(count) {}
    void arrive_and_wait();

   private:
    const std::uint32_t count_;
    std::atomic<std::uint32_t> arrived_{0}, phase_{0};
  };

  std::vector<Simulator*> parts_;
  Duration lookahead_;
  unsigned threads_;  // the calling one included
  std::vector<std::thread> workers_;
  Barrier start_, done_;  // around each window
  Time window_end_{};
  std::function<void(std::size_t)> prepare_;
  bool stopping_ = false;
  std::uint64_t windows_ = 0;
};

}  // namespace masnet::sim
