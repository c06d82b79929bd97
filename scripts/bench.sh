#!/usr/bin/env bash
# Usage: scripts/bench.sh [Google Benchmark flags, e.g. --benchmark_filter=ScenarioA]
# Builds the benchmark suite in Release and runs it on one thread. The counter
# particle_step_time is the time of one step divided by the particle count.
# Then runs bullet_peer_bench, Bullet 3 on the shared rigid-body scenes (bench/rigid), with the
# same flags (a filter that matches none of its cases only makes it say so);
# MAS_SKIP_BULLET_PEER=1 leaves it out. Last node_bench (bench/node): the node's two halves of a
# published frame, the world thread's copy against the publishing thread's messages.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
# Bullet and pkg-config, which finds it, only for the benchmarks: run and test do not need them.
mas_install_missing libbullet-dev pkg-config
MAS_BUILD_TYPE=Release mas_build engine_bench bullet_peer_bench node_bench
"${WS_DIR}/devel/lib/mass_aggregate_sim/engine_bench" "$@"
if [ "${MAS_SKIP_BULLET_PEER:-0}" != "1" ]; then
  "${WS_DIR}/devel/lib/mass_aggregate_sim/bullet_peer_bench" "$@"
fi
"${WS_DIR}/devel/lib/mass_aggregate_sim/node_bench" "$@"
