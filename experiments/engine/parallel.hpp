// Independent pieces of work spread over a few threads: each thread takes the next index as it
// finishes one, so a long piece does not hold the others back. Used where the pieces are known
// up front and each writes only its own result (the index's paragraphs, the advice sample's
// searches); the queue of a sweep has its own scheduler (sweep.hpp).
#pragma once

#include <cstddef>
#include <functional>

namespace mpmstab {

// work(i) for every i in [0, n), on up to `threads` threads (the calling one among them); the
// first exception thrown, in index order, is rethrown once every piece has ended. The caller's
// open run account (cached_run.hpp) is open on every thread that works.
void for_each_in_parallel(std::size_t n, unsigned threads,
                          const std::function<void(std::size_t)>& work);

// The CPUs this process may run on: its affinity mask, which taskset or a Slurm job's CPU
// allocation sets (at least 1; all the machine's where the mask cannot be read).
unsigned available_cpus();

}  // namespace mpmstab
