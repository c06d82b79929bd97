#!/usr/bin/env bash
# Builds the gtest suites (engine and node, no ROS master needed) a second time with
# AddressSanitizer and UndefinedBehaviorSanitizer in their own workspace, runs them, and writes
# their JUnit XML into the folder given as $1. Any sanitizer report fails the test binary.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
out_dir="$1"
asan_ws="${MAS_ASAN_WS:-${WS_DIR}-asan}"
flags="-O1 -g -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
mas_build_in "${asan_ws}" -DCMAKE_BUILD_TYPE=Debug -DMAS_BUILD_BENCHMARKS=OFF \
  "-DCMAKE_CXX_FLAGS=${flags}" "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined" \
  "-DCMAKE_SHARED_LINKER_FLAGS=-fsanitize=address,undefined" -- all tests
mkdir -p "${out_dir}"
# The sanitized binaries must load the sanitized libraries: an environment that sourced the normal
# workspace (test.sh's first stage) puts its devel/lib on LD_LIBRARY_PATH, which outranks the
# binaries' run path.
export LD_LIBRARY_PATH="${asan_ws}/devel/lib${LD_LIBRARY_PATH:+:${LD_LIBRARY_PATH}}"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:halt_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=${REPO_DIR}/test/sanitizers/lsan.supp:print_suppressions=0"
status=0
for binary in "${asan_ws}"/devel/lib/mass_aggregate_sim/*_tests; do
  [ -x "${binary}" ] || continue
  name="$(basename "${binary}")"
  engine_library="$(ldd "${binary}" | awk '/libmass_aggregate_sim_engine/ {print $3}')"
  if [ "${engine_library#"${asan_ws}"/}" = "${engine_library}" ]; then
    message="${name} would load ${engine_library}, not the sanitized engine in ${asan_ws}"
    echo "${message}" >&2
    status=1
    mas_failure_xml "${out_dir}/asan-${name}.xml" "asan-${name}" sanitizers "${name}" "${message}"
    continue
  fi
  echo "== ${name} under ASan+UBSan"
  if ! "${binary}" --gtest_output="xml:${out_dir}/asan-${name}.xml" >"${asan_ws}/${name}.log" 2>&1; then
    status=1
    tail -n 40 "${asan_ws}/${name}.log"
    # A sanitizer abort leaves no XML: record the failure so the count sees it.
    if [ ! -s "${out_dir}/asan-${name}.xml" ]; then
      mas_failure_xml "${out_dir}/asan-${name}.xml" "asan-${name}" sanitizers "${name}" \
        "sanitizer or crash: see ${asan_ws}/${name}.log"
    fi
  fi
  grep -E "^\[  (PASSED|FAILED) " "${asan_ws}/${name}.log" || true
done
exit "${status}"
