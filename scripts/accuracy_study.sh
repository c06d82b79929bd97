#!/usr/bin/env bash
# Usage: scripts/accuracy_study.sh OUTDIR
# Builds and runs the accuracy study (bench/study), then plots its CSV files into PNGs in OUTDIR:
# work-precision and error-vs-dt per particle problem, the stability map, the energy drift, and
# for the rigid-body problems work-precision and error-against-iterations per substep count.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
if [ $# -ne 1 ]; then
  echo "usage: $0 OUTDIR" >&2
  exit 2
fi
mkdir -p "$1"
OUT_DIR="$(cd "$1" && pwd)"
# The plots need gnuplot; the tests do not, so it is installed here rather than in common.sh.
APT_PACKAGES+=(gnuplot-nox)
mas_install_missing
mas_build accuracy_study
"${WS_DIR}/devel/lib/mass_aggregate_sim/accuracy_study" "${OUT_DIR}"
gnuplot -e "dir='${OUT_DIR}'" "${REPO_DIR}/scripts/accuracy_plots.gp"
echo "Wrote to ${OUT_DIR}:"
ls "${OUT_DIR}"
