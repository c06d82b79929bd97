#!/usr/bin/env bash
# Installs what is missing, builds, and starts the simulator on the default scene.
# Extra arguments go to roslaunch, e.g. scripts/run.sh rviz:=true scene:=pile
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
mas_install_missing
mas_build
exec roslaunch mass_aggregate_sim sim.launch "$@"
