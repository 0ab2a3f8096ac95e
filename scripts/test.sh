#!/usr/bin/env bash
# Install, build and run every test (what CI runs).
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
install_packages
configure_and_build -DSUPERBALL_BUILD_TESTS=ON
cd "$BUILD_DIR"
ctest --output-on-failure -j "$(nproc)"
