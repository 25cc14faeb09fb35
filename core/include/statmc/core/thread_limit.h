// How core honours a thread count without touching process-wide state: work runs inside
// a TBB arena of that size, so that two callers with different limits never interfere.
#pragma once

#include <tbb/task_arena.h>

namespace statmc {

/// Runs `body` with at most `nthreads` worker threads; 0 (or less) means all cores.
template <class Body>
void run_with_threads(int nthreads, Body&& body)
{
    if (nthreads <= 0) {
        body();
        return;
    }
    tbb::task_arena arena(nthreads);
    arena.execute(body);
}

}  // namespace statmc
