#!/bin/bash
# Session 17's quality ladder (docs/BENCHMARKS.md, "2026-11-28, session 17"): every rigid scene
# with sleeping off at every setting registered, ours (engine_bench, substeps x iterations from
# 1 x 1 to 12 x 1) and then Bullet 3.24 (bullet_peer_bench, double, 10 iterations, 1 to 16
# substeps), one program after the other, to compare the cost of reaching an at-rest quality.
# Build both first (scripts/bench.sh builds them), then from the repository root:
#   flock /tmp/mas_build.lock bash docs/benchmarks/rigid_2026-11-28_session17_ladder.sh \
#     > docs/benchmarks/rigid_2026-11-28_session17_ladder.txt
set -u
lib="${MAS_WS:-$HOME/mass_aggregate_sim_ws}/devel/lib"
echo "# $(uname -srm); $(grep -m1 'model name' /proc/cpuinfo); $(nproc) cores"
echo "# engine $(git rev-parse --short HEAD); $(sha256sum "$lib/libmass_aggregate_sim_engine.so")"
echo "== ours $(date -u +%T) load $(cut -d' ' -f1 /proc/loadavg)"
"$lib/mass_aggregate_sim/engine_bench" \
  --benchmark_filter='BM_Rigid(Pyramid|Stack|RandomDrop|ParticleRain)/[0-9]+/[0-9]+/0/' \
  --benchmark_counters_tabular=true 2>/dev/null | grep -E '^BM_|^Benchmark'
echo "== bullet $(date -u +%T) load $(cut -d' ' -f1 /proc/loadavg)"
"$lib/mass_aggregate_sim/bullet_peer_bench" \
  --benchmark_filter='BM_Bullet_(RigidPyramid|RigidStack|RandomDrop|ParticleRain)/[0-9]+/[0-9]+/0/' \
  --benchmark_counters_tabular=true 2>/dev/null | grep -E '^BM_|^Benchmark'
echo "== end $(date -u +%T)"
