#!/bin/bash
# Session 18's pyramid ladder (docs/BENCHMARKS.md, "2026-11-28, session 18"): session 17's ladder
# (rigid_2026-11-28_session17_ladder.sh) on the pyramids only, after the lever-rule load guess:
# Box2D's pyramids of 210 and 5,050 and the dropped pyramid of 210 (rigid_scenes.h), ours at
# every setting registered, then Bullet 3.24 (double, 10 iterations) at 1 to 16 substeps (the
# 5,050 up to 8), sleeping off, one program after the other. Build both first
# (scripts/bench.sh builds them), then from the repository root:
#   flock /tmp/mas_build.lock bash docs/benchmarks/rigid_2026-11-28_session18_pyramid_ladder.sh \
#     > docs/benchmarks/rigid_2026-11-28_session18_pyramid_ladder.txt
set -u
exec bash "$(dirname "$0")/rigid_ladder.sh" '(Dropped)?Pyramid' \
  'RigidPyramid|DroppedPyramid'
