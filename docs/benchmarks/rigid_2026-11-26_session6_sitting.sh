#!/bin/bash
# Session 6 (2026-11-26): the body solver's separations taken in the warm start's sweep and the
# coupled masses' well-conditioned inverses, before (ee74ece) against after, alternating rounds.
# Each directory holds an engine_bench and the libmass_aggregate_sim_engine.so it was built with
# (the binary's run path would otherwise load the workspace's):
#   bash docs/benchmarks/rigid_2026-11-26_session6_sitting.sh ROUNDS DIR_BEFORE DIR_AFTER
rounds=$1
shift
filter='BM_Rigid(Pyramid/20/4/[01]/2|Pyramid/100/4/[01]/2|Pyramid/100/8/[01]/1|Stack/20/4/0/2|RandomDrop/1000/4/0/[23]|ParticleRain/2000/4/0/2)/'
for dir in "$@"; do sha256sum "$dir/libmass_aggregate_sim_engine.so"; done
for ((i = 1; i <= rounds; ++i)); do
  if ((i % 2 == 1)); then order=("$@"); else order=("${@:2}" "$1"); fi
  for dir in "${order[@]}"; do
    echo "## round $i $dir $(date -u +%T) load $(cut -d' ' -f1 /proc/loadavg)"
    LD_LIBRARY_PATH="$dir" "$dir/engine_bench" --benchmark_filter="$filter" \
      --benchmark_counters_tabular=true 2>&1 | grep '^BM_'
  done
done
