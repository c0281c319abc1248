#include "sim/cpus.hpp"

#include <sched.h>

#include <algorithm>
#include <thread>

namespace masnet::sim {

int allowed_cpu_count() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) == 0) return std::max(1, CPU_COUNT(&set));
  // No affinity mask to read: fall back on the machine's count.
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

}  // namespace masnet::sim
