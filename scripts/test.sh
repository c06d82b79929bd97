#!/usr/bin/env bash
# Installs what is missing, builds, runs every test, and ends with the line "N passed, N failed"
# counted from the JUnit XML result files. Exits non-zero on any failure. The stages:
#   1. Release build; gtest (engine, node) and rostest through `catkin_make run_tests`
#   2. the gtest suites again under AddressSanitizer + UndefinedBehaviorSanitizer
#   3. each libFuzzer target for MAS_FUZZ_SECONDS (default 60) under ASan + UBSan
# MAS_SKIP_SANITIZERS=1 / MAS_SKIP_FUZZ=1 skip stages 2 / 3 while iterating locally (CI sets neither).
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
mas_install_missing "${TEST_APT_PACKAGES[@]}"
mas_build all tests

results="${WS_DIR}/build/test_results"
rm -rf "${results}"
set +e
(cd "${WS_DIR}" && catkin_make run_tests -j1 >"${WS_DIR}/test.log" 2>&1)
run_status=$?
set -e
grep -E "^\[ *(OK|FAILED|PASSED) *\]|^\[ (order|energy) \]|^\[Testcase|FAILURE|ERROR" \
  "${WS_DIR}/test.log" | tail -n 300 || true
# The soak test's figures (requests handled, RSS) are in its result file, not in the log.
grep -ho "\[ soak \][^&<]*" "${results}"/*/rosunit-soak.xml 2>/dev/null || true
if [ "${run_status}" -ne 0 ]; then
  echo "catkin_make run_tests exited ${run_status}; see ${WS_DIR}/test.log" >&2
fi

sanitizer_status=0
if [ "${MAS_SKIP_SANITIZERS:-0}" != "1" ]; then
  set +e
  bash "${REPO_DIR}/scripts/sanitizer_tests.sh" "${results}/sanitizers"
  sanitizer_status=$?
  set -e
fi

fuzz_status=0
if [ "${MAS_SKIP_FUZZ:-0}" != "1" ]; then
  set +e
  bash "${REPO_DIR}/scripts/fuzz.sh" "${results}/fuzz"
  fuzz_status=$?
  set -e
fi

# The closing "N passed, N failed" line, counted from the result files themselves.
set +e
/usr/bin/python3 "${REPO_DIR}/scripts/count_results.py" "${results}"
count_status=$?
set -e
[ "${count_status}" -eq 0 ] && [ "${run_status}" -eq 0 ] && [ "${sanitizer_status}" -eq 0 ] &&
  [ "${fuzz_status}" -eq 0 ]
