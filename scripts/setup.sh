#!/usr/bin/env bash
# Installs PeNa's Debian 12 build dependencies (only those missing) and builds into build/.
# Idempotent: a second run installs nothing and rebuilds only what changed.
# Environment: PENA_BUILD_DIR (default build), PENA_WERROR (ON in CI), PENA_JOBS (default nproc),
# PENA_TARGETS (default: everything; the demo builds only what it runs), PENA_BROWSER_TESTS (default
# 1: also install Debian's chromium, node and the browser test's npm packages in
# tests/console/node_modules; 0: skip them, the browser test then reports itself skipped). Uses
# ccache if present.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake pkg-config
  libeigen3-dev libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev
  libprotobuf-dev protobuf-compiler libspdlog-dev libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev libnanoflann-dev zlib1g-dev libsodium-dev libssl-dev openssl
  libfastrtps-dev fastddsgen
  libboost-dev nlohmann-json3-dev
  libcpp-httplib-dev  # the console's server-library benchmark (tests/console/bench_web_server)
  lintian help2man adduser  # the Debian packages: their test, manual pages, pena-services' postinst
  clang libclang-rt-14-dev  # the sanitizer and libFuzzer build (scripts/sanitizers.sh, scripts/fuzz.sh)
)

# The console's browser test (tests/console): Debian's chromium (large, so only when wanted) and
# node for puppeteer-core.
if [[ ${PENA_BROWSER_TESTS:-1} == 1 ]]; then
  packages+=(chromium)
  command -v node >/dev/null 2>&1 || packages+=(nodejs npm)
fi

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  if [[ $(id -u) -ne 0 ]]; then
    echo "setup: installing packages needs root (run as root, or install them yourself)" >&2
    exit 1
  fi
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# puppeteer-core at the version package-lock.json pins, into tests/console/node_modules.
if [[ ${PENA_BROWSER_TESTS:-1} == 1 && ! -d tests/console/node_modules/puppeteer-core ]]; then
  echo "setup: npm ci in tests/console (puppeteer-core for the browser test)"
  (cd tests/console && PUPPETEER_SKIP_DOWNLOAD=1 npm ci --no-audit --no-fund >/dev/null)
fi

build_dir=${PENA_BUILD_DIR:-build}
jobs=${PENA_JOBS:-$(nproc)}
# Pass -DPENA_WERROR only when asked: flipping a cached option would rebuild everything.
# Line tables only (-g1): backtraces keep their functions and lines, and the build takes about a
# fifth less time than with full debug info (CI's budget is 30 minutes on 2 cores). Debug builds
# (cmake -DCMAKE_BUILD_TYPE=Debug) keep full debug info.
config=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG")
if [[ "${CI:-}" == "true" ]]; then config+=(-DPENA_WERROR=ON); fi
if [[ -n "${PENA_WERROR:-}" ]]; then config+=(-DPENA_WERROR="$PENA_WERROR"); fi
# ccache, when the machine has it, makes a rebuild after a branch switch or a clean checkout cheap;
# it is not installed here, since a first build gains nothing from it.
if command -v ccache >/dev/null 2>&1; then config+=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi

cmake -S . -B "$build_dir" "${config[@]}" >/dev/null
targets=()
for target in ${PENA_TARGETS:-}; do targets+=(--target "$target"); done
cmake --build "$build_dir" -j "$jobs" "${targets[@]}"
