#pragma once
// The part of the window benchmarks (windows.cpp, rank_windows.cpp): one event per microsecond of
// simulated time, each scheduling the next, so that every window of one lookahead has work.
#include "sim/simulator.hpp"

namespace masnet::bench {

struct Ticker {
  sim::Simulator sim;
  void tick() {
    sim.after(sim::Duration{1000}, [this] { tick(); });
  }
};

}  // namespace masnet::bench
