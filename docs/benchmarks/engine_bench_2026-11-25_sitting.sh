#!/bin/bash
cd /tmp/sitting1
{
echo "# sitting start $(date -u +%FT%TZ) load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# before: engine of 5db094a (bench sources of 4992cc2 with a naming shim), LD_LIBRARY_PATH=/tmp/sitting1/before before/engine_bench --benchmark_counters_tabular=true"
LD_LIBRARY_PATH=/tmp/sitting1/before ./before/engine_bench --benchmark_counters_tabular=true
echo "# before end $(date -u +%FT%TZ) load $(cut -d' ' -f1-3 /proc/loadavg)"
} > before.txt 2>&1
{
echo "# after start $(date -u +%FT%TZ) load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# after: 4992cc2, LD_LIBRARY_PATH=/tmp/sitting1/after after/engine_bench --benchmark_counters_tabular=true"
LD_LIBRARY_PATH=/tmp/sitting1/after ./after/engine_bench --benchmark_counters_tabular=true
echo "# after end $(date -u +%FT%TZ) load $(cut -d' ' -f1-3 /proc/loadavg)"
} > after.txt 2>&1
for r in 1 2 3; do
 for w in before after; do
  echo "# round $r $w $(date -u +%FT%TZ) load $(cut -d' ' -f1-3 /proc/loadavg)"
  LD_LIBRARY_PATH=/tmp/sitting1/$w ./$w/engine_bench --benchmark_filter='ScenarioA_FreeFall/|ScenarioB_SpringChains/|ScenarioC_GroundGrid|ScenarioC_ColliderMix|ScenarioD_SettledPile/100000|BandwidthFloor' --benchmark_counters_tabular=true 2>&1 | grep -E "^BM_"
 done
done > rounds.txt 2>&1
echo done > finished
