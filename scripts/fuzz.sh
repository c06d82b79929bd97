#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) and runs each for a bounded time
# (MAS_FUZZ_SECONDS, default 60). Writes one JUnit XML per target into the folder given as $1
# and prints the executions. A crash saves its input under the workspace; copy it into
# test/fuzz/regressions/ (named <target>-<what>) so the gtest suite replays it forever after.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
out_dir="$1"
seconds="${MAS_FUZZ_SECONDS:-60}"
fuzz_dir="${WS_DIR}-fuzz"
mkdir -p "${out_dir}" "${fuzz_dir}"
eigen_include="$(pkg-config --cflags-only-I eigen3)"
# Targets that use the node's sources need its generated message headers (made by the main
# catkin build, which scripts/test.sh runs first); ROS's own headers are in /usr/include.
msg_include="${WS_DIR}/devel/include"
status=0
for target_src in "${REPO_DIR}"/test/fuzz/*_fuzz.cpp; do
  target="$(basename "${target_src}" .cpp)"
  corpus_name="${target%_fuzz}_corpus"
  binary="${fuzz_dir}/${target}"
  # The engine target needs only the engine sources; other targets list theirs in a
  # "// fuzz-sources:" line (globs relative to the repo root).
  extra_sources=()
  extra_flags=()
  while read -r pattern; do
    for f in ${REPO_DIR}/${pattern}; do extra_sources+=("$f"); done
  done < <(sed -n 's#^// fuzz-sources: ##p' "${target_src}" | tr ' ' '\n')
  while read -r flag; do
    [ -n "${flag}" ] && extra_flags+=("${flag}")
  done < <(sed -n 's#^// fuzz-flags: ##p' "${target_src}" | tr ' ' '\n')
  # The engine's own compile options (CMakeLists.txt) come first.
  clang++ -std=c++17 -O1 -g -ffp-contract=off -fno-math-errno -Wno-psabi \
    -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
    -I"${REPO_DIR}/include" -I"${REPO_DIR}/src" -I"${msg_include}" ${eigen_include} "${target_src}" \
    $(find "${REPO_DIR}/src/engine" -name '*.cpp' | sort) \
    "${extra_sources[@]}" "${extra_flags[@]}" -o "${binary}" >"${fuzz_dir}/${target}.build.log" 2>&1 || {
    tail -n 30 "${fuzz_dir}/${target}.build.log"
    echo "fuzz target ${target} failed to build" >&2
    status=1
    mas_failure_xml "${out_dir}/fuzz-${target}.xml" fuzz fuzz "${target}" \
      "build failed: see ${fuzz_dir}/${target}.build.log"
    continue
  }
  work_corpus="${fuzz_dir}/${corpus_name}"
  mkdir -p "${work_corpus}"
  [ -d "${REPO_DIR}/test/fuzz/${corpus_name}" ] && cp -n "${REPO_DIR}/test/fuzz/${corpus_name}"/* "${work_corpus}/" 2>/dev/null || true
  log="${fuzz_dir}/${target}.log"
  set +e
  (cd "${fuzz_dir}" && "${binary}" -max_total_time="${seconds}" -max_len=4096 -print_final_stats=1 \
    -artifact_prefix="${fuzz_dir}/${target}-" "${work_corpus}" >"${log}" 2>&1)
  rc=$?
  set -e
  execs="$(sed -n 's/^stat::number_of_executed_units: *//p' "${log}" | tail -n 1)"
  echo "fuzz ${target}: ${execs:-0} executions in ${seconds} s, exit ${rc}"
  if [ "${rc}" -eq 0 ]; then
    cat >"${out_dir}/fuzz-${target}.xml" <<XML
<testsuite name="fuzz" tests="1" failures="0" errors="0">
  <testcase classname="fuzz" name="${target}_${seconds}s_${execs:-0}_executions"/>
</testsuite>
XML
  else
    status=1
    tail -n 40 "${log}"
    mas_failure_xml "${out_dir}/fuzz-${target}.xml" fuzz fuzz "${target}" \
      "crash or broken promise: see ${log}"
  fi
done
exit "${status}"
