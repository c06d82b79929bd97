#!/bin/bash
# Session 18's pyramid ladder (docs/BENCHMARKS.md, "2026-11-28, session 18"): session 17's ladder
# (rigid_2026-11-28_session17_ladder.sh) on the pyramids only, after the lever-rule load guess:
# Box2D's pyramids of 210 and 5,050 and the dropped pyramid of 210 (rigid_scenes.h), ours at
# every setting registered, then Bullet 3.24 (double, 10 iterations) at 1 to 16 substeps (the
# 5,050 up to 8), sleeping off, one program after the other. Build both first
# (scripts/bench.sh builds them), then from the repository root:
#   flock /tmp/mas_build.lock bash docs/benchmarks/rigid_2026-11-28_session18_pyramid_ladder.sh \
#     > docs/benchmarks/rigid_2026-11-28_session18_pyramid_ladder.txt
set -u
lib="${MAS_WS:-$HOME/mass_aggregate_sim_ws}/devel/lib"
echo "# $(uname -srm); $(grep -m1 'model name' /proc/cpuinfo); $(nproc) cores"
echo "# engine $(git rev-parse --short HEAD) + the working tree; $(sha256sum "$lib/libmass_aggregate_sim_engine.so")"
echo "== ours $(date -u +%T) load $(cut -d' ' -f1 /proc/loadavg)"
"$lib/mass_aggregate_sim/engine_bench" \
  --benchmark_filter='BM_Rigid(Dropped)?Pyramid/[0-9]+/[0-9]+/0/' \
  --benchmark_counters_tabular=true 2>/dev/null | grep -E '^BM_|^Benchmark'
echo "== bullet $(date -u +%T) load $(cut -d' ' -f1 /proc/loadavg)"
"$lib/mass_aggregate_sim/bullet_peer_bench" \
  --benchmark_filter='BM_Bullet_(Rigid|Dropped)Pyramid/[0-9]+/[0-9]+/0/' \
  --benchmark_counters_tabular=true 2>/dev/null | grep -E '^BM_|^Benchmark'
echo "== end $(date -u +%T)"
