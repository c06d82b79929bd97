#!/bin/bash
# The ladder of settings (docs/BENCHMARKS.md, "2026-11-28, session 17") for the scenes named by
# a regular expression over the benchmark names' scene part: ours at every setting registered,
# then Bullet 3.24 (double, 10 iterations) at every substep count registered, sleeping off, one
# program after the other. Build both first (scripts/bench.sh builds them), then from the
# repository root, e.g. for the dropped pyramid:
#   flock /tmp/mas_build.lock bash docs/benchmarks/rigid_ladder.sh DroppedPyramid > OUT.txt
# Session 19 ran that on a tried variant of the engine:
# rigid_2026-11-28_session19_slop_gap_tried_dropped_ladder.txt.
# Ours are named BM_Rigid<Scene>/..., Bullet's BM_Bullet_<Scene>/... except that Box2D's pyramid
# and the stacks are BM_Bullet_Rigid<Scene>: a second regular expression, if given, is Bullet's.
set -u
ours="${1:?usage: rigid_ladder.sh SCENE_REGEX [BULLET_SCENE_REGEX]}"
bullet="${2:-$1}"
lib="${MAS_WS:-$HOME/mass_aggregate_sim_ws}/devel/lib"
echo "# $(uname -srm); $(grep -m1 'model name' /proc/cpuinfo); $(nproc) cores"
echo "# engine $(git rev-parse --short HEAD) + the working tree; $(sha256sum "$lib/libmass_aggregate_sim_engine.so")"
echo "== ours $(date -u +%T) load $(cut -d' ' -f1 /proc/loadavg)"
"$lib/mass_aggregate_sim/engine_bench" \
  --benchmark_filter="BM_Rigid(${ours})/[0-9]+/[0-9]+/0/" \
  --benchmark_counters_tabular=true 2>/dev/null | grep -E '^BM_|^Benchmark'
echo "== bullet $(date -u +%T) load $(cut -d' ' -f1 /proc/loadavg)"
"$lib/mass_aggregate_sim/bullet_peer_bench" \
  --benchmark_filter="BM_Bullet_(${bullet})/[0-9]+/[0-9]+/0/" \
  --benchmark_counters_tabular=true 2>/dev/null | grep -E '^BM_|^Benchmark'
echo "== end $(date -u +%T)"
