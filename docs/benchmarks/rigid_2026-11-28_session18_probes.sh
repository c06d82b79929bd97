#!/bin/bash
# Session 18's probe runs (docs/BENCHMARKS.md, "2026-11-28, session 18"): the pyramid probes run
# against two engine libraries, BASE (before the lever rule: 28ced03's library) and KEPT (with
# it), each a directory holding libmass_aggregate_sim_engine.so. From the repository root:
#   bash docs/benchmarks/rigid_2026-11-28_session18_probes.sh BASE KEPT \
#     > docs/benchmarks/rigid_2026-11-28_session18_probes.txt
set -u
base=$1
kept=$2
ws="${MAS_WS:-$HOME/mass_aggregate_sim_ws}"
for probe in pyramid_ke_probe pyramid_jitter_probe; do
  g++ -std=c++17 -O2 -I include -I bench/rigid -I /usr/include/eigen3 \
    "docs/benchmarks/$probe.cpp" bench/rigid/rigid_scenes.cpp -o "/tmp/$probe" \
    -L "$ws/devel/lib" -lmass_aggregate_sim_engine
done
run() {  # run LIBDIR ENV... -- PROBE ARGS...
  local lib=$1
  shift
  env LD_LIBRARY_PATH="$lib" "$@"
}
echo "# $(uname -srm); $(grep -m1 'model name' /proc/cpuinfo); $(date -u +%FT%T)"
echo "# BASE $(sha256sum "$base/libmass_aggregate_sim_engine.so")"
echo "# KEPT $(sha256sum "$kept/libmass_aggregate_sim_engine.so")"
echo "== 1. Box2D's 210 pyramid, 4 x 2, sleeping off: KE at 1, 3, 5 and 10 s (pyramid_ke_probe)"
for lib in base kept; do
  dir=$base
  [ "$lib" = kept ] && dir=$kept
  for switch in "" GUESSFROM=1 GUESSUNTIL=1; do
    echo "-- $lib ${switch:-defaults}"
    run "$dir" $switch /tmp/pyramid_ke_probe 20 4 2 | sed -n '1p;3p;5p;10p' | cut -d';' -f1
  done
done
echo "== 2. Box2D's 5,050 pyramid, 4 x 2, sleeping off, 600 frames: KE at 1, 5 and 10 s, and the run's time"
for lib in base kept; do
  dir=$base
  [ "$lib" = kept ] && dir=$kept
  echo "-- $lib"
  start=$(date +%s.%N)
  run "$dir" /tmp/pyramid_ke_probe 100 4 2 | sed -n '1p;5p;10p' | cut -d';' -f1
  echo "seconds $(echo "$(date +%s.%N) - $start" | bc)"
done
echo "== 3. The 210 pyramid set off its layout, 4 x 2, sleeping off: KE at 2 and 10 s (pyramid_jitter_probe base jitter gap seed frames spacing)"
for args in "20 0 0 1 600 1.01" "20 0.002 0 1 600 1.01" "20 0.002 0 2 600 1.01" "20 0.002 0 3 600 1.01" \
  "20 0.004 0 1 600 1.01" "20 0.002 0 1 600 1" "20 0.02 0 1 600 1" "20 0.002 0.0001 1 600 1.01" \
  "20 0.002 0.001 1 600 1.01"; do
  for lib in base kept; do
    dir=$base
    [ "$lib" = kept ] && dir=$kept
    echo "-- $lib $args: $(run "$dir" /tmp/pyramid_jitter_probe $args | sed -n '1p;5p' | tr '\n' ' ')"
  done
done
echo "== 4. The same with switches, 20 0.002 0 1 600 1 (boxes touching, so some start 0 to 4 mm into a neighbour)"
for switch in NOSHOCK=1 NOGUESS=1 GUESSFROM=1; do
  for lib in base kept; do
    dir=$base
    [ "$lib" = kept ] && dir=$kept
    echo "-- $lib $switch: $(run "$dir" $switch /tmp/pyramid_jitter_probe 20 0.002 0 1 600 1 | sed -n '1p;5p' | tr '\n' ' ')"
  done
done
echo "== 5. The 5,050 pyramid set off its layout (touching, so some start in a neighbour), sleeping on: when all 5,050 sleep (s, checked every 0.25 s up to 5 s)"
for jitter in 0.002 0.01; do
  for seed in 1 2 3 4 5 6; do
    for lib in base kept; do
      dir=$base
      [ "$lib" = kept ] && dir=$kept
      asleep=$(run "$dir" SLEEP=1 PERIOD=15 /tmp/pyramid_jitter_probe 100 $jitter 0 $seed 300 1 |
        awk '$6 >= 5050 {print $2; exit}')
      echo "-- $lib jitter $jitter seed $seed: ${asleep:-not within 5 s}"
    done
  done
done
echo "== end $(date -u +%T)"
