#!/usr/bin/env bash
# Coverage-guided fuzzing of every decoder of outside input (docs/fuzzing.md): builds the
# libFuzzer targets of tests/fuzz (clang, AddressSanitizer + UBSan; scripts/sanitizers.sh) and
# runs each for SECONDS on its seed corpus, one after the other. Prints libFuzzer's final figures
# per target (runs, runs/s, cov, ft, corpus) and exits 1 if any target crashed; the crashing input is
# left in the work dir (crash-*, leak-*, timeout-*, oom-*) to add to tests/fuzz/corpus/<target>/.
# usage: scripts/fuzz.sh [SECONDS] [TARGET...]     (default 60 s, every target)
# Environment: PENA_FUZZ_SKIP (targets a run over all leaves out), PENA_ASAN_BUILD_DIR
# (default build-asan), PENA_FUZZ_WORK (default
# <build dir>/fuzz-work: the corpus each run grows, kept between runs), PENA_JOBS.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-60}
shift || true
all=(fuzz_carmen fuzz_mission_log fuzz_relations fuzz_tum fuzz_line_csv fuzz_svg_plan fuzz_dxf_plan
     fuzz_line_map_codec fuzz_link_frame fuzz_link_session fuzz_link_open fuzz_service_config
     fuzz_from_dds fuzz_dds_convert fuzz_browser_request)
targets=("$@")
if ((${#targets[@]} == 0)); then
  # PENA_FUZZ_SKIP: targets left out of a run over all (a finding being worked on).
  for target in "${all[@]}"; do
    [[ " ${PENA_FUZZ_SKIP:-} " == *" $target "* ]] && echo "fuzz: $target skipped (PENA_FUZZ_SKIP)" && continue
    targets+=("$target")
  done
fi

build_dir=${PENA_ASAN_BUILD_DIR:-build-asan}
PENA_TARGETS="${targets[*]}" PENA_ASAN_BUILD_ONLY=1 bash scripts/sanitizers.sh
work=${PENA_FUZZ_WORK:-$build_dir/fuzz-work}

export ASAN_OPTIONS=halt_on_error=1:detect_leaks=1
# The file readers' targets write every input to a file: into memory where the machine allows.
if [[ -z ${TMPDIR:-} && -w /dev/shm ]]; then export TMPDIR=/dev/shm; fi
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
failed=()
for target in "${targets[@]}"; do
  mkdir -p "$work/$target/corpus"
  log="$work/$target/fuzz.log"
  # New inputs go to the work corpus; the seeds in the repo are only read. -timeout: an input
  # taking over 10 s is a finding; -rss_limit_mb: so is a decoder that needs 2 GB.
  if "$build_dir/tests/fuzz/$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
      -print_final_stats=1 -artifact_prefix="$work/$target/" \
      "$work/$target/corpus" "tests/fuzz/corpus/$target" >"$log" 2>&1; then
    status=ok
  else
    status=FAILED
    failed+=("$target")
  fi
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
  last=$(grep -E '^#[0-9]+' "$log" | tail -n 1 | grep -oE 'cov: [0-9]+ ft: [0-9]+ corp: [0-9]+/[0-9]+[a-zA-Z]*' || true)
  printf 'fuzz: %-22s %4s s  %9s runs  %6s runs/s  %s  %s\n' "$target" "$seconds" "${runs:-?}" \
    "${rate:-?}" "${last:-}" "$status"
done
if ((${#failed[@]})); then
  echo "fuzz: ${failed[*]} failed; see $work/<target>/fuzz.log and the crash-* inputs beside it" >&2
  exit 1
fi
