#pragma once
// The clocks behind the timings the outputs report (wall_time_s, cpu_time_s).
#include <chrono>
#include <ctime>

namespace shpb {

// Wall time since `t`, s (the steady clock: clock adjustments do not move it).
inline double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// Processor time of the whole process (every thread), s: on a shared machine the wall time
// depends on the others' load, the processor time much less.
inline double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

}  // namespace shpb
