#!/bin/bash
# The random drop's liveliness and overlap after it settles, over many seeds (docs/BENCHMARKS.md,
# 2026-11-27 session 10): for each seed and engine, the kinetic energy at each whole second from
# 6 s to 15 s, sorted (its median is the figure compared: single avalanches make the mean and the
# maximum jump by tenfold), and the probe's "late" line (the last 3 s of 15 s).
# Each DIR holds a random_drop_probe built against its engine and that engine's .so:
#   g++ -std=c++17 -O2 -I include -I bench/rigid -I /usr/include/eigen3 \
#     docs/benchmarks/random_drop_probe.cpp bench/rigid/rigid_scenes.cpp -o DIR/random_drop_probe \
#     -L DIR -lmass_aggregate_sim_engine
# Usage: bash rigid_2026-11-27_session10_random_drop_ke.sh "SEEDS" ITERATIONS DIR...
seeds="$1"; iterations="$2"; shift 2
for seed in $seeds; do
  for dir in "$@"; do
    out=$(SEED=$seed ITER=$iterations LD_LIBRARY_PATH=$dir $dir/random_drop_probe 4 900)
    ke=$(echo "$out" | grep '^t ' | awk '$2+0>=6 {print $5}' | sort -g | tr '\n' ' ')
    echo "seed $seed $(basename $dir): KE 6-15 s sorted: $ke | $(echo "$out" | grep '^late')"
  done
done
