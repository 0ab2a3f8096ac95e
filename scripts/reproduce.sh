#!/usr/bin/env bash
# Install, build and run the main job: `superball reproduce` on the paper's scenes.
# Usage: scripts/reproduce.sh [options of superball reproduce]   (report/ by default)
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
install_packages
configure_and_build -DSUPERBALL_BUILD_TESTS=OFF -DSUPERBALL_BUILD_BENCH=OFF
cd "$ROOT"
"$BUILD_DIR/cli/superball" reproduce "$@"
