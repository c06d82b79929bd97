#!/usr/bin/env bash
# The rigid-body sitting of 2026-11-26: the engine's bodies (engine_bench, BM_Rigid*) and Bullet
# 3.24 in double precision (bullet_peer_bench) on the shared scenes of bench/rigid, one after the
# other on the same machine, both from `MAS_SKIP_BULLET_PEER=0 bash scripts/bench.sh` builds.
set -euo pipefail
bin="${MAS_WS:-${HOME}/mass_aggregate_sim_ws}/devel/lib/mass_aggregate_sim"
echo "# $(date -u +%Y-%m-%dT%H:%M:%SZ) commit $(git -C "$(dirname "$0")/../.." rev-parse --short HEAD)"
uptime
"${bin}/engine_bench" --benchmark_filter='BM_Rigid' --benchmark_counters_tabular=true
uptime
"${bin}/bullet_peer_bench" --benchmark_counters_tabular=true
uptime
