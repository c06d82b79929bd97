#!/bin/bash
# Issue 13's budget, session 5 of 2026-11-26: main at a79fe0e ("head") against 5db094a (main
# before the engine redesign), the quick particle scenes in five alternating rounds, run under the
# build lock so that no build or test runs beside it:
#   flock /tmp/mas_build.lock bash docs/benchmarks/engine_bench_2026-11-26_session5_sitting.sh
# Each binary sits in /tmp/sit3/<name>/ with its own libmass_aggregate_sim_engine.so
# (LD_LIBRARY_PATH outranks the binary's run path). head: built Release from a79fe0e. 5db094a:
# built Release in its own workspace from a detached worktree, with the bench/ sources of 4992cc2
# and the shim of the sitting of 2026-11-26 (engine_bench_2026-11-26_sitting.sh): an
# engine/world/world.h including its engine/world.h, and World::addCollider / addGenerator
# forwarding to addPlane / addSphere / addBox / addCapsule / addSpring; no engine code changed
# (engine_bench_5db094a_shim.patch, with the commands that rebuild it).
set -u
cd /tmp/sit3
out=rounds.txt
quick='ScenarioA_FreeFall/|ScenarioA_BandwidthFloor/|ScenarioB_SpringChains/|ScenarioC_GroundGrid|ScenarioC_ColliderMix|ScenarioD_SettledPile/|ScenarioD_FrictionPile/|ScenarioDPrime_DroppedPile/(1000|10000)/'
orders=("head 5db" "5db head" "head 5db" "5db head" "head 5db")
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
    LD_LIBRARY_PATH=/tmp/sit3/$w ./$w/engine_bench --benchmark_filter="$quick" \
        --benchmark_counters_tabular=true 2>&1 | grep -E '^(BM_|Benchmark)'
    echo "# round $r $w quick end $(stamp)"
  done
done
echo "# sitting end $(stamp)"
} > "$out" 2>&1
kill "$monitor"
echo done > finished
