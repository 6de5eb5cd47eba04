#pragma once
// Runs independent jobs 0..count−1 on a few worker threads. Each job writes only its own result
// slot, so the results do not depend on the thread count or on the order jobs finish in.
#include <cstddef>
#include <functional>

namespace shpb {

// `job(i)` is called once for every i in [0, count). `threads` ≤ 0 means all cores.
// `progress(done, count)` is called after each finished job, serialised (never concurrently).
// The first exception thrown by a job (e.g. Interrupted) stops the remaining jobs and is
// rethrown here after all workers have joined.
void run_parallel(std::size_t count, int threads, const std::function<void(std::size_t)>& job,
                  const std::function<void(std::size_t, std::size_t)>& progress = {});

// The thread count `threads` resolves to (≤ 0: hardware concurrency, at least 1).
int resolve_threads(int threads);

}  // namespace shpb
