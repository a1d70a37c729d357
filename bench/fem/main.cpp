// Entry point of serosa_bench_fem.
#include <benchmark/benchmark.h>

BENCHMARK_MAIN();
