# Shared set-up for scripts/run.sh and scripts/test.sh: installs what is missing, builds the
# package in a catkin workspace outside the source tree, and sources it. Sourced, not executed.
set -euo pipefail

REPO_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# The catkin workspace, outside the source tree: a workspace inside the package would put a second
# copy of every executable under the package folder, and `rosrun mass_aggregate_sim node` would
# then find several. MAS_WS names another place.
# roslaunch keeps its logs under $HOME/.ros too, so make sure HOME is set.
export HOME="${HOME:-$(getent passwd "$(id -u)" | cut -d: -f6)}"
WS_DIR="${MAS_WS:-${HOME}/mass_aggregate_sim_ws}"
# Debian's ROS needs Debian's python (catkin_pkg), not a pyenv interpreter first on PATH.
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"

APT_PACKAGES=(
  build-essential cmake
  ros-core-dev catkin rosbash libroscpp-dev libtf2-ros-dev libgeometry-msgs-dev
  libvisualization-msgs-dev libsensor-msgs-dev python3-sensor-msgs libstd-srvs-dev
  libros-rosgraph-msgs-dev librostest-dev python3-rostest
  python3-rosbag python3-geometry-msgs python3-visualization-msgs python3-std-srvs python3-rospy
  python3-tf2-ros
  libactionlib-dev python3-actionlib libactionlib-msgs-dev python3-actionlib-msgs
  libdynamic-reconfigure-config-init-mutex-dev python3-dynamic-reconfigure
  libdiagnostic-updater-dev libdiagnostic-msgs-dev python3-diagnostic-msgs
  libeigen3-dev libyaml-cpp-dev googletest libgtest-dev libgmock-dev libbenchmark-dev
  ${MAS_EXTRA_APT_PACKAGES:-}
)
# Needed only by scripts/test.sh: clang's libFuzzer for the fuzzing stage.
TEST_APT_PACKAGES=(clang libclang-rt-14-dev pkg-config)

# mas_install_missing [extra packages...]: installs whatever of APT_PACKAGES and the extras is missing.
mas_install_missing() {
  local missing=()
  local pkg
  for pkg in "${APT_PACKAGES[@]}" "$@"; do
    if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$pkg")
    fi
  done
  if ((${#missing[@]})); then
    echo "Installing missing packages: ${missing[*]}"
    local sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
      "${missing[@]}" >/dev/null
  fi
}

# mas_build_in WS [cmake args...] -- [targets...]: builds the package in workspace WS.
mas_build_in() {
  local ws="$1"
  shift
  local cmake_args=()
  while (($#)) && [ "$1" != "--" ]; do
    cmake_args+=("$1")
    shift
  done
  (($#)) && shift
  mkdir -p "${ws}/src"
  ln -sfn "${REPO_DIR}" "${ws}/src/mass_aggregate_sim"
  (
    cd "${ws}"
    catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCATKIN_ENABLE_TESTING=ON \
      "${cmake_args[@]}" -j"${MAS_JOBS:-$(nproc)}" "$@" >"${ws}/build.log" 2>&1 || {
      tail -n 60 "${ws}/build.log"
      echo "Build failed: full log in ${ws}/build.log" >&2
      exit 1
    }
  )
}

# mas_build [targets...]: the normal build in WS_DIR, then sources it.
mas_build() {
  # shellcheck disable=SC2086
  mas_build_in "${WS_DIR}" -DCMAKE_BUILD_TYPE="${MAS_BUILD_TYPE:-Release}" ${MAS_CMAKE_ARGS:-} \
    -- "$@"
  set +u
  # shellcheck disable=SC1091
  source "${WS_DIR}/devel/setup.bash"
  set -u
}

# mas_sanitizer_ws: the workspace of the clang build with the sanitizers (scripts/sanitizer_tests.sh),
# whose libraries the fuzz targets link (scripts/fuzz.sh).
mas_sanitizer_ws() {
  echo "${MAS_SANITIZER_WS:-${WS_DIR}-sanitize}"
}

# mas_failure_xml FILE SUITE CLASS NAME MESSAGE: a JUnit file with one failed test case, for a
# stage that could not produce its own (build failure, crash), so the closing count sees it.
mas_failure_xml() {
  cat >"$1" <<XML
<testsuite name="$2" tests="1" failures="1" errors="0">
  <testcase classname="$3" name="$4"><failure message="$5"/></testcase>
</testsuite>
XML
}
