#pragma once
// How many CPUs this process may run on: the affinity mask (taskset, cgroups' cpusets, a
// batch system's binding), not the machine's core count.

namespace masnet::sim {

/// The number of CPUs in this process's affinity mask; at least 1.
int allowed_cpu_count();

}  // namespace masnet::sim
