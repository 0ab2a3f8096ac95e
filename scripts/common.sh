# Shared by scripts/reproduce.sh and scripts/test.sh: install Debian 12's
# packages, configure and build.  Source it; it sets BUILD_DIR.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build}"

PACKAGES=(
  build-essential cmake pkg-config ninja-build          # toolchain (Ninja: see CMAKE_GENERATOR below)
  libginac-dev libcln-dev libeigen3-dev libmpfr-dev     # symbolic and numeric backends (MPFR: digits:N)
  libtomlplusplus-dev nlohmann-json3-dev libcli11-dev   # scene files, JSON, command line
  libgtest-dev libbenchmark-dev                         # tests and benchmarks
  texlive-latex-base gnuplot-nox python3-sympy          # LaTeX check, plots, the SymPy reference
  doxygen                                               # the API reference (docs/CMakeLists.txt)
  clang libclang-rt-14-dev                              # the sanitized build and libFuzzer (scripts/test.sh stages 2, 3)
  libopenmpi-dev openmpi-bin                            # the MPI runner (scripts/test.sh stage 1)
  pybind11-dev python3-dev python3-numpy                # the Python module (python/), for /usr/bin/python3
  python3-pytest python3-nbclient python3-ipykernel python3-matplotlib  # its tests and notebook
)

install_packages() {
  local missing=()
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  echo "installing: ${missing[*]}"
  $sudo apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
}

# A new build folder is configured for Ninja (a folder configured before keeps its
# generator): Ninja compiles a target's objects while the libraries it links are
# still being built, where Make waits for each library, and keeps both cores of
# the CI machine busy through the long test builds.
export CMAKE_GENERATOR="${CMAKE_GENERATOR:-Ninja}"

# configure_and_build [cmake options…] [--target T]: configure BUILD_DIR, build (T or everything).
configure_and_build() {
  local options=() target=()
  while [ $# -gt 0 ]; do
    if [ "$1" = "--target" ]; then target=(--target "$2"); shift 2; else options+=("$1"); shift; fi
  done
  cmake -S "$ROOT" -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release "${options[@]}"
  cmake --build "$BUILD_DIR" -j "$(nproc)" "${target[@]}"
}
