#!/bin/bash
# The particle-scene sitting of 2026-11-26: HEAD (e2e2427) against 4992cc2 (the last commit before
# rigid bodies entered the engine) and 5db094a (main before the engine redesign), alternating
# rounds, run under the build lock so that no build or test runs beside it:
#   flock /tmp/mas_build.lock bash docs/benchmarks/engine_bench_2026-11-26_sitting.sh
# Each binary sits in /tmp/sitting2/<name>/ with its own libmass_aggregate_sim_engine.so
# (LD_LIBRARY_PATH outranks the binary's run path), built Release in its own catkin workspace from
# a detached worktree: head = e2e2427 and 4992cc2 with their own bench/ sources (the particle
# scenes' sources are the same in both: `git diff 4992cc2 e2e2427 -- bench/*.cpp bench/*.h` only
# adds dynamic_tree_bench.cpp); 5db094a = its engine with the bench/*.cpp and bench/*.h of 4992cc2
# and a shim (world/world.h forwarding to its world.h; addCollider/addGenerator forwarding to
# addPlane/addSphere/addBox/addCapsule/addSpring), no engine code changed.
# Rounds: five of the quick scenes (A, the floor, B, C, D, D with friction, D' at 1,000 and
# 10,000), three of the slow ones (D' at 100,000 with --benchmark_min_time=2, the dense drop); the
# order of the three binaries rotates each round. A background loop samples the busiest processes
# every 30 s into monitor.txt.
set -u
cd /tmp/sitting2
out=rounds.txt
quick='ScenarioA_FreeFall/|ScenarioA_BandwidthFloor/|ScenarioB_SpringChains/|ScenarioC_GroundGrid|ScenarioC_ColliderMix|ScenarioD_SettledPile/|ScenarioD_FrictionPile/|ScenarioDPrime_DroppedPile/(1000|10000)/'
slow='ScenarioDPrime_DroppedPile/100000/|DenseDrop'
orders=("head 4992cc2 5db094a" "4992cc2 5db094a head" "5db094a head 4992cc2" "head 4992cc2 5db094a" "4992cc2 5db094a head")
stamp() { echo "$(date -u +%FT%TZ) load $(cut -d' ' -f1-3 /proc/loadavg)"; }
( while true; do echo "## $(stamp)"; ps -eo pid,pcpu,etimes,comm --sort=-pcpu | head -5; sleep 30; done ) > monitor.txt 2>&1 &
monitor=$!
{
echo "# sitting start $(stamp)"
echo "# $(uname -srm); $(grep -m1 'model name' /proc/cpuinfo); $(nproc) cores"
sha256sum */engine_bench */libmass_aggregate_sim_engine.so
for r in 1 2 3 4 5; do
  for w in ${orders[$((r - 1))]}; do
    echo "# round $r $w quick start $(stamp)"
    LD_LIBRARY_PATH=/tmp/sitting2/$w ./$w/engine_bench --benchmark_filter="$quick" \
        --benchmark_counters_tabular=true 2>&1 | grep -E '^(BM_|Benchmark)'
    echo "# round $r $w quick end $(stamp)"
  done
  if [ "$r" -le 3 ]; then
    for w in ${orders[$((r - 1))]}; do
      echo "# round $r $w slow start $(stamp)"
      LD_LIBRARY_PATH=/tmp/sitting2/$w ./$w/engine_bench --benchmark_filter="$slow" \
          --benchmark_min_time=2 --benchmark_counters_tabular=true 2>&1 | grep -E '^(BM_|Benchmark)'
      echo "# round $r $w slow end $(stamp)"
    done
  fi
done
echo "# sitting end $(stamp)"
} > "$out" 2>&1
kill "$monitor"
echo done > finished
