#!/usr/bin/env bash
# Installs what is missing, builds, and starts the simulator on the default scene.
# Extra arguments go to roslaunch, e.g. scripts/run.sh scene:=bridge rviz:=true
# (rviz:=true also installs RViz when it is missing).
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
extra=()
for arg in "$@"; do
  [ "${arg}" = "rviz:=true" ] && extra+=(rviz)
done
mas_install_missing "${extra[@]}"
mas_build
exec roslaunch mass_aggregate_sim sim.launch "$@"
