#!/usr/bin/env bash
# Sets up (scripts/setup.sh) and runs every test suite with CTest. This is the README's test
# command and exactly what CI runs (.ci/run).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
build_dir=${PENA_BUILD_DIR:-build}
# Any DDS participant a test starts stays on this machine (see deploy/dds/pena-loopback.xml).
export FASTRTPS_DEFAULT_PROFILES_FILE="$PWD/deploy/dds/pena-loopback.xml"
ctest --test-dir "$build_dir" --output-on-failure -j "${PENA_JOBS:-$(nproc)}"
# libpena's unit tests and every decoder's fuzz corpus under AddressSanitizer + UBSan, then a
# short fuzz run per decoder (docs/fuzzing.md; PENA_FUZZ_S seconds each, 0 skips it).
bash scripts/sanitizers.sh
if [[ ${PENA_FUZZ_S:-20} != 0 ]]; then
  bash scripts/fuzz.sh "${PENA_FUZZ_S:-20}"
fi
