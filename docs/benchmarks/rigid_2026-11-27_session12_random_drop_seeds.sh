#!/bin/bash
# The 1,000-box random drop's at-rest quality over many seeds, from the benchmark programs
# themselves (docs/BENCHMARKS.md, 2026-11-27 session 12): for each seed, each engine DIR (an
# engine_bench with its .so beside it) and Bullet, one line of BM_*RandomDrop/1000/4/0[/2]'s
# counters: kinetic energy, the late overlaps and how many boxes moved more than 1 mm and 1 cm
# over the last 3 s of the untimed 10 s (rigid_report.h).
# Usage: bash rigid_2026-11-27_session12_random_drop_seeds.sh "SEEDS" BULLET_PEER_BENCH DIR...
seeds="$1"; bullet="$2"; shift 2
for seed in $seeds; do
  for dir in "$@"; do
    echo "seed $seed $(basename "$dir"): $(MAS_RIGID_SEED=$seed LD_LIBRARY_PATH=$dir "$dir/engine_bench" \
      --benchmark_filter='BM_RigidRandomDrop/1000/4/0/2/' 2>/dev/null | grep '^BM_')"
  done
  echo "seed $seed bullet: $(MAS_RIGID_SEED=$seed "$bullet" \
    --benchmark_filter='BM_Bullet_RandomDrop/1000/4/0/' 2>/dev/null | grep '^BM_')"
done
