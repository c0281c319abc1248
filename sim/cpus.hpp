#pragma once
// How many processors this process may run on: what `taskset`, a container's cpuset or a
// batch scheduler left it, not how many the machine has.

namespace masnet::sim {

/// The processors in this process's affinity mask (at least 1). Falls back to
/// std::thread::hardware_concurrency() where the mask cannot be read.
int allowed_cpu_count();

}  // namespace masnet::sim
