#!/bin/bash
# Session 17's quality ladder (docs/BENCHMARKS.md, "2026-11-28, session 17"): every rigid scene
# with sleeping off at every setting registered, ours (engine_bench, substeps x iterations from
# 1 x 1 to 12 x 1) and then Bullet 3.24 (bullet_peer_bench, double, 10 iterations, 1 to 16
# substeps), one program after the other, to compare the cost of reaching an at-rest quality.
# Build both first (scripts/bench.sh builds them), then from the repository root:
#   flock /tmp/mas_build.lock bash docs/benchmarks/rigid_2026-11-28_session17_ladder.sh \
#     > docs/benchmarks/rigid_2026-11-28_session17_ladder.txt
set -u
exec bash "$(dirname "$0")/rigid_ladder.sh" 'Pyramid|Stack|RandomDrop|ParticleRain' \
  'RigidPyramid|RigidStack|RandomDrop|ParticleRain'
