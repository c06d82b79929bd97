#!/bin/bash
# One sitting of the quick particle scenes (issue 13's budget) and the particle rain, binaries
# side by side in alternating rounds, under the build lock so that no build or test runs beside it:
#   flock /tmp/mas_build.lock bash docs/benchmarks/particle_sitting.sh DIR ROUNDS NAME...
# Each binary sits in DIR/NAME/ with its own libmass_aggregate_sim_engine.so (LD_LIBRARY_PATH
# outranks the binary's run path). Writes DIR/rounds.txt (Google Benchmark's rows, the machine,
# the binaries' SHA-256 and the load at each start) and DIR/monitor.txt (the busiest processes
# every 30 s); the ratios: engine_bench_2026-11-26_ratios.py DIR/rounds.txt NAME,NAME.
set -u
dir=$1
rounds=$2
shift 2
names=("$@")
cd "$dir"
quick='ScenarioA_FreeFall/|ScenarioA_BandwidthFloor/|ScenarioB_SpringChains/|ScenarioC_GroundGrid|ScenarioC_ColliderMix|ScenarioD_SettledPile/|ScenarioD_FrictionPile/|ScenarioDPrime_DroppedPile/(1000|10000)/|ScenarioDPrime_DroppedPileSeeds/1000/|RigidParticleRain/2000/4/0/'
stamp() { echo "$(date -u +%FT%TZ) load $(cut -d' ' -f1-3 /proc/loadavg)"; }
( while true; do echo "## $(stamp)"; ps -eo pid,pcpu,etimes,comm --sort=-pcpu | head -5; sleep 30; done ) > monitor.txt 2>&1 &
monitor=$!
{
  echo "# sitting start $(stamp)"
  echo "# $(uname -srm); $(grep -m1 'model name' /proc/cpuinfo); $(nproc) cores"
  for name in "${names[@]}"; do sha256sum "$name/engine_bench" "$name/libmass_aggregate_sim_engine.so"; done
  for ((r = 1; r <= rounds; ++r)); do
    order=("${names[@]}")
    # Even rounds run the binaries in the reverse order.
    if ((r % 2 == 0)); then
      order=()
      for ((i = ${#names[@]} - 1; i >= 0; --i)); do order+=("${names[$i]}"); done
    fi
    for name in "${order[@]}"; do
      echo "# round $r $name quick start $(stamp)"
      LD_LIBRARY_PATH="$dir/$name" "./$name/engine_bench" --benchmark_filter="$quick" \
          --benchmark_counters_tabular=true 2>&1 | grep -E '^(BM_|Benchmark)'
      echo "# round $r $name quick end $(stamp)"
    done
  done
  echo "# sitting end $(stamp)"
} > rounds.txt 2>&1
kill "$monitor"
