#!/usr/bin/env bash
# Builds PeNa's Debian packages (libpena-dev, pena-tools, pena-services; docs/deploy.md) into
# dist/ (or the directory given as $1): sets up and builds (scripts/setup.sh), then runs cpack in
# the build tree. Environment: as scripts/setup.sh (PENA_BUILD_DIR, PENA_JOBS, ...).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
build_dir=${PENA_BUILD_DIR:-build}
out=$(realpath -m "${1:-dist}")
mkdir -p "$out"
(cd "$build_dir" && cpack -G DEB -B "$out/_cpack")
mv "$out"/_cpack/*.deb "$out/"
rm -rf "$out/_cpack"
ls -l "$out"/*.deb
echo "install with: apt install $out/*.deb   (then docs/deploy.md: configure and start the units)"
