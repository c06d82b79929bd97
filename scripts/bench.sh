#!/usr/bin/env bash
# Usage: scripts/bench.sh [Google Benchmark flags, e.g. --benchmark_filter=ScenarioA]
# Builds the benchmark suite in Release and runs it on one thread. The counter
# particle_step_time is the time of one step divided by the particle count.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
mas_install_missing
MAS_BUILD_TYPE=Release mas_build engine_bench
"${WS_DIR}/devel/lib/mass_aggregate_sim/engine_bench" "$@"
