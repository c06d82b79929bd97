#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) against the engine and node libraries of
# the sanitizer workspace (scripts/sanitizer_tests.sh builds them instrumented for coverage; this
# builds them there first if needed) and runs each target for a bounded time (MAS_FUZZ_SECONDS,
# default 60). Writes one JUnit XML per target into the folder given as $1 and prints the
# executions. A crash saves its input under the workspace; copy it into test/fuzz/regressions/
# (named <target>-<what>) so the gtest suite replays it forever after.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
out_dir="$1"
seconds="${MAS_FUZZ_SECONDS:-60}"
fuzz_dir="${WS_DIR}-fuzz"
san_ws="$(mas_sanitizer_ws)"
san_lib="${san_ws}/devel/lib"
mkdir -p "${out_dir}" "${fuzz_dir}"
if [ ! -e "${san_lib}/libmass_aggregate_sim_ros.so" ]; then
  bash "${REPO_DIR}/scripts/sanitizer_tests.sh" "${fuzz_dir}/sanitizer-results" >/dev/null
fi
eigen_include="$(pkg-config --cflags-only-I eigen3)"
status=0
for target_src in "${REPO_DIR}"/test/fuzz/*_fuzz.cpp; do
  target="$(basename "${target_src}" .cpp)"
  corpus_name="${target%_fuzz}_corpus"
  binary="${fuzz_dir}/${target}"
  # A target links the engine; one that needs more names its libraries in a "// fuzz-libraries:"
  # line and any other linker flags in a "// fuzz-flags:" line.
  libraries=(mass_aggregate_sim_engine)
  extra_flags=()
  while read -r library; do
    [ -n "${library}" ] && libraries=("${library}" "${libraries[@]}")
  done < <(sed -n 's#^// fuzz-libraries: ##p' "${target_src}" | tr ' ' '\n')
  while read -r flag; do
    [ -n "${flag}" ] && extra_flags+=("${flag}")
  done < <(sed -n 's#^// fuzz-flags: ##p' "${target_src}" | tr ' ' '\n')
  link=()
  for library in "${libraries[@]}"; do link+=("-l${library}"); done
  # The engine's own compile options (CMakeLists.txt) come first.
  clang++ -std=c++17 -O1 -g1 -ffp-contract=off -fno-math-errno -Wno-psabi \
    -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
    -I"${REPO_DIR}/include" -I"${REPO_DIR}/src" -I"${san_ws}/devel/include" ${eigen_include} \
    "${target_src}" -L"${san_lib}" -Wl,-rpath,"${san_lib}" "${link[@]}" "${extra_flags[@]}" \
    -o "${binary}" >"${fuzz_dir}/${target}.build.log" 2>&1 || {
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
  (cd "${fuzz_dir}" && LD_LIBRARY_PATH="${san_lib}" "${binary}" -max_total_time="${seconds}" \
    -max_len=4096 -print_final_stats=1 -artifact_prefix="${fuzz_dir}/${target}-" \
    "${work_corpus}" >"${log}" 2>&1)
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
