#!/bin/bash
# Session 11's sitting (docs/BENCHMARKS.md, "2026-11-27, session 11"): the rigid scenes with the
# engine before (4d16cfc) and after (020ce0b) in two alternating rounds, then ours after and
# Bullet 3.24 (double, 10 iterations) at 4 substeps, one round each. Each engine_bench sits in
# /tmp/ab/NAME/ with its own libmass_aggregate_sim_engine.so; bullet_peer_bench in /tmp/ab/.
#   flock /tmp/mas_build.lock bash docs/benchmarks/rigid_2026-11-27_session11_sitting.sh
set -u
rigid='BM_RigidPyramid/20/4/[01]/2|BM_RigidPyramid/100/4/[01]/2|BM_RigidPyramid/100/8/1/1|BM_RigidStack/20/4/0/2|BM_RigidRandomDrop/1000/4/0/[23]|BM_RigidParticleRain/2000/4/0/2'
run() {
  echo "== $1 $(date -u +%T) load $(cut -d' ' -f1 /proc/loadavg)"
  LD_LIBRARY_PATH=/tmp/ab/$1 /tmp/ab/$1/engine_bench --benchmark_filter="$2" \
    --benchmark_counters_tabular=true 2>/dev/null | grep -E '^BM_|^Benchmark'
}
echo "# $(uname -srm); $(grep -m1 'model name' /proc/cpuinfo); $(nproc) cores"
sha256sum /tmp/ab/4d16cfc/libmass_aggregate_sim_engine.so /tmp/ab/020ce0b/libmass_aggregate_sim_engine.so
run 4d16cfc "$rigid"
run 020ce0b "$rigid"
run 020ce0b "$rigid"
run 4d16cfc "$rigid"
echo "== bullet $(date -u +%T) load $(cut -d' ' -f1 /proc/loadavg)"
/tmp/ab/bullet_peer_bench --benchmark_filter='RigidPyramid/20/4/[01]|RigidPyramid/100/4/[01]|RigidStack/20/4/0|RandomDrop/1000/4/0|ParticleRain/2000/4/0' \
  --benchmark_counters_tabular=true 2>/dev/null | grep -E '^BM_|^Benchmark'
echo "== end $(date -u +%T)"
