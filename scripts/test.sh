#!/usr/bin/env bash
# Installs what is missing, builds, runs every test (gtest and rostest), and ends with the line
# "N passed, N failed" computed from the test result files. Exits non-zero on any failure.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
mas_install_missing
mas_build all tests

results="${WS_DIR}/build/test_results"
rm -rf "${results}"
set +e
(cd "${WS_DIR}" && catkin_make run_tests -j1 >"${WS_DIR}/test.log" 2>&1)
run_status=$?
set -e
grep -E "^\[ *(RUN|OK|FAILED|PASSED) *\]|^\[Testcase|FAILURE|ERROR" "${WS_DIR}/test.log" \
  | grep -vE "^\[ RUN" | tail -n 200 || true
if [ "${run_status}" -ne 0 ]; then
  echo "catkin_make run_tests exited ${run_status}; see ${WS_DIR}/test.log" >&2
fi
# The closing "N passed, N failed" line, counted from the result files themselves.
set +e
/usr/bin/python3 "${REPO_DIR}/scripts/count_results.py" "${results}"
count_status=$?
set -e
[ "${count_status}" -eq 0 ] && [ "${run_status}" -eq 0 ]
