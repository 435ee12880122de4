// The benches' main, linked into each: the CLI's process settings first
// (core/process_settings.h), so the figures are what a user of the CLI gets.
#include <benchmark/benchmark.h>

#include "core/process_settings.h"

int main(int argc, char** argv) {
  isegman::restart_with_process_settings(argv);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
