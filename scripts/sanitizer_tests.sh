#!/usr/bin/env bash
# Builds the gtest suites (engine and node, no ROS master needed) a second time with clang,
# AddressSanitizer and UndefinedBehaviorSanitizer in their own workspace, runs them, and writes
# their JUnit XML into the folder given as $1. Any sanitizer report fails the test binary.
# The libraries also count the edges they run (libFuzzer's inline 8-bit counters and PC table),
# so that scripts/fuzz.sh links its targets against them instead of compiling the engine again.
# Not -fsanitize=fuzzer-no-link: its comparison tracing made every test 3.5 times slower here.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
out_dir="$1"
san_ws="$(mas_sanitizer_ws)"
# -g1 (line tables only) keeps the reports' file:line and costs a third of the compile time of -g.
flags="-O1 -g1 -fsanitize=address,undefined -fno-sanitize-recover=undefined"
flags+=" -fno-omit-frame-pointer -fsanitize-coverage=inline-8bit-counters,pc-table"
link_flags="-fsanitize=address,undefined"
mas_build_in "${san_ws}" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG= \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DMAS_BUILD_BENCHMARKS=OFF \
  "-DCMAKE_CXX_FLAGS=${flags}" "-DCMAKE_EXE_LINKER_FLAGS=${link_flags}" \
  "-DCMAKE_SHARED_LINKER_FLAGS=${link_flags}" -- engine_tests node_tests
mkdir -p "${out_dir}"
# The sanitized binaries must load the sanitized libraries: an environment that sourced the normal
# workspace (test.sh's first stage) puts its devel/lib on LD_LIBRARY_PATH, which outranks the
# binaries' run path.
export LD_LIBRARY_PATH="${san_ws}/devel/lib${LD_LIBRARY_PATH:+:${LD_LIBRARY_PATH}}"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:halt_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=${REPO_DIR}/test/sanitizers/lsan.supp:print_suppressions=0"
# Long physics runs whose outcome the Release stage checks and whose code every shorter test
# already runs under the sanitizers (together 7 of the 9 minutes the suite took here).
long_runs="Stacks.PyramidOfAHundred*:DenseDrop.*:RandomPile.*"
long_runs+=":Extremes.TimeStepsFromAMicrosecondToATenthOfASecond"
status=0
for binary in "${san_ws}"/devel/lib/mass_aggregate_sim/*_tests; do
  [ -x "${binary}" ] || continue
  name="$(basename "${binary}")"
  engine_library="$(ldd "${binary}" | awk '/libmass_aggregate_sim_engine/ {print $3}')"
  if [ "${engine_library#"${san_ws}"/}" = "${engine_library}" ]; then
    message="${name} would load ${engine_library}, not the sanitized engine in ${san_ws}"
    echo "${message}" >&2
    status=1
    mas_failure_xml "${out_dir}/asan-${name}.xml" "asan-${name}" sanitizers "${name}" "${message}"
    continue
  fi
  echo "== ${name} under ASan+UBSan"
  if ! "${binary}" --gtest_filter="-${long_runs}" --gtest_output="xml:${out_dir}/asan-${name}.xml" \
    >"${san_ws}/${name}.log" 2>&1; then
    status=1
    tail -n 40 "${san_ws}/${name}.log"
    # A sanitizer abort leaves no XML: record the failure so the count sees it.
    if [ ! -s "${out_dir}/asan-${name}.xml" ]; then
      mas_failure_xml "${out_dir}/asan-${name}.xml" "asan-${name}" sanitizers "${name}" \
        "sanitizer or crash: see ${san_ws}/${name}.log"
    fi
  fi
  grep -E "^\[  (PASSED|FAILED) " "${san_ws}/${name}.log" || true
done
exit "${status}"
