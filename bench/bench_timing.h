// How every micro-benchmark here is timed: wall-clock milliseconds, reported as the
// aggregates (median among them) of repeated runs, since this machine's timings vary.
#pragma once

#include <benchmark/benchmark.h>

inline benchmark::internal::Benchmark* timed(benchmark::internal::Benchmark* b, int repetitions)
{
    return b->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Repetitions(repetitions)
        ->ReportAggregatesOnly();
}

inline void median_of_5(benchmark::internal::Benchmark* b) { timed(b, 5); }
/// For the slow kernels (scalar, reference): 3 repetitions.
inline void median_of_3(benchmark::internal::Benchmark* b) { timed(b, 3); }
/// For the reference filter: one iteration per repetition, 3 repetitions.
inline void median_of_3_single(benchmark::internal::Benchmark* b) { timed(b, 3)->Iterations(1); }
