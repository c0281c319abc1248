// PHOLD on the masnet kernel (the workload: phold_workload.hpp). The checksum printed must
// equal the ns-3 peer's (tests/bench/peers/phold_ns3.cc) for the same arguments.
//   masnet_bench_phold --lps=100 --m=10 --events=1e7 [--warmup=N] [--ties=origin]
// --ties=origin runs the kernel's origin order (docs/time-and-ordering.md), each LP its own
// origin, to measure what it costs; the checksum is the peer's unless two events tie.
#include <string_view>

#include "phold_workload.hpp"
#include "sim/simulator.hpp"

using namespace masnet;

namespace {

struct Phold {
  sim::Simulator sim;
  bench::PholdWorkload work;

  explicit Phold(const bench::Args& args) : work(args) {}
  void handle(std::uint32_t lp) {
    if (work.count(lp)) {
      sim.stop();
      return;
    }
    const std::uint32_t dst = work.random_lp();
    // In the origin order the event runs as its LP (owner dst + 1); otherwise the owner is
    // ignored.
    sim.at_for(dst + 1, sim.now() + sim::Duration{work.delay_ticks()},
               [this, dst] { handle(dst); });
  }
};

}  // namespace

int main(int argc, char** argv) {
  const bench::Args args{argc, argv};
  Phold p{args};
  const char* ties = args.find("ties");
  if (ties && std::string_view{ties} == "origin") p.sim.order_ties_by_origin();
  p.sim.reserve(p.work.population() + 16);
  for (std::uint32_t lp = 0; lp < p.work.lps; ++lp) {
    p.sim.act_as(lp + 1);  // each LP schedules its own first events
    for (std::uint32_t j = 0; j < p.work.initial_per_lp; ++j)
      p.sim.after(sim::Duration{p.work.delay_ticks()}, [&p, lp] { p.handle(lp); });
  }
  p.sim.run();
  p.work.print_result("masnet");
  return 0;
}
