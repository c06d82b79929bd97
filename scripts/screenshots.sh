#!/usr/bin/env bash
# Takes the README's RViz screenshots from the real RViz under Xvfb: for each SCENE[:SECONDS]
# argument, starts sim.launch paused with that scene and its view (config/<scene>.rviz) on a
# master of its own (a random port, so nothing else running is touched), steps it SECONDS of
# simulated time (default 4) with ~step, grabs the screen into docs/rviz_<scene>.png and stops
# what it started.
#   bash scripts/screenshots.sh pyramid:6 capsule_chain:3 particle_rain:2.5
# Installs RViz, Xvfb and ImageMagick if missing (only this script needs them), builds first.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
mas_install_missing rviz xvfb xauth imagemagick
mas_build
shots=("$@")
((${#shots[@]})) || shots=(pyramid:6 capsule_chain:3 particle_rain:2.5)
for shot in "${shots[@]}"; do
  scene="${shot%%:*}"
  seconds="${shot#*:}"
  [ "${seconds}" = "${shot}" ] && seconds=4
  port=$((20000 + RANDOM % 20000))
  out="${REPO_DIR}/docs/rviz_${scene}.png"
  echo "${scene}: ${seconds} s on port ${port} -> ${out}"
  # RViz needs a few seconds to start; the paused scene is then stepped exactly SECONDS of
  # simulated time (in ~step calls of at most 1000 steps).
  ROS_MASTER_URI="http://localhost:${port}" xvfb-run -a -s "-screen 0 1200x800x24" bash -c '
    roslaunch -p "$1" mass_aggregate_sim sim.launch scene:="$2" view:="$2" rviz:=true \
      paused:=true >/dev/null 2>&1 &
    launch=$!
    sleep 12
    rate="$(rosparam get /mass_aggregate_sim/rate)"
    steps="$(python3 -c "print(round($3 * ${rate}))")"
    while [ "${steps}" -gt 0 ]; do
      n=$((steps > 1000 ? 1000 : steps))
      rosservice call /mass_aggregate_sim/step "steps: ${n}" >/dev/null
      steps=$((steps - n))
    done
    sleep 2
    import -window root "$4"
    kill -INT "${launch}"
    wait "${launch}"
  ' screenshot "${port}" "${scene}" "${seconds}" "${out}"
done
