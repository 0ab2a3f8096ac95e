#!/usr/bin/env bash
# Install, build and run every test (what CI runs), in four stages:
#   1. the test suite (Release build with the Python module and the MPI runner, ctest: its pytest tests and
#      notebook too), then the install: `cmake --install` into a temporary prefix,
#      examples/cpp built and run against it (CMake and pkg-config), the Python module
#      imported from it and the notebook run against it, and the Debian package
#      (cpack), installed with apt-get, used, purged
#   2. the same suite built with clang++, AddressSanitizer + UndefinedBehaviorSanitizer, where the tests
#      whose work is repetition of one code path run fewer repetitions (SUPERBALL_TEST_SCALE=small)
#   3. the libFuzzer target over scene parsing and solving (built in stage 2's folder), 60 s from
#      tests/fuzz/corpus
#   4. the red-team suite (tests/redteam), hostile scenes and command lines for 60 s
# STAGES="1" (or "1 2", …) runs a subset; FUZZ_SECONDS changes stage 3's length, FUZZ_SEED its seed;
# REDTEAM_SECONDS and REDTEAM_SEED the same for stage 4.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
STAGES="${STAGES:-1 2 3 4}"
FUZZ_SECONDS="${FUZZ_SECONDS:-60}"
FUZZ_SEED="${FUZZ_SEED:-1}"
REDTEAM_SECONDS="${REDTEAM_SECONDS:-60}"
REDTEAM_SEED="${REDTEAM_SEED:-1}"
install_packages
export LSAN_OPTIONS="suppressions=$ROOT/tests/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1"
summary="$(mktemp)"
trap 'rm -f "$summary"' EXIT
# run_ctest DIR LABEL [FILTER [ctest options…]]: the suite in DIR, its output through FILTER
# (default cat); its closing line goes to the summary.
run_ctest() {
  local dir="$1" label="$2" filter="${3:-cat}" log
  shift $(($# < 3 ? $# : 3))
  log="$(mktemp)"
  (cd "$dir" && ctest --output-on-failure -j "$(nproc)" "$@") 2>&1 | $filter | tee "$log"
  grep -E "tests passed, [0-9]+ tests failed out of" "$log" | sed "s/^/$label: /" >> "$summary"
  rm -f "$log"
}

# install_check: install BUILD_DIR into a temporary prefix, build examples/cpp against
# that prefix only (find_package, then pkg-config), run it and the installed command.
install_check() {
  local work prefix
  work="$(mktemp -d)"
  prefix="$work/prefix"
  cmake --install "$BUILD_DIR" --prefix "$prefix" > "$work/install.log"
  cmake -S "$ROOT/examples/cpp" -B "$work/example" -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix" > "$work/configure.log"
  cmake --build "$work/example" -j "$(nproc)"
  "$work/example/superball_example"
  # Every superball library the example loads comes from the prefix, none from the build tree.
  if ldd "$work/example/superball_example" | grep libsuperball_ | grep -v -- "=> $prefix/"; then
    echo "install: the example loads a superball library from outside $prefix" >&2
    exit 1
  fi
  local pc="$prefix/lib/pkgconfig"
  [ -d "$pc" ] || pc="$(dirname "$(find "$prefix" -name superball.pc | head -n 1)")"
  # shellcheck disable=SC2046
  c++ -std=c++17 -O1 -o "$work/example-pc" "$ROOT/examples/cpp/main.cpp" \
    -DSUPERBALL_EXAMPLE_SCENE="\"$prefix/share/superball/scenes/paper-4.4-alpha2.toml\"" \
    $(PKG_CONFIG_PATH="$pc" pkg-config --cflags --libs superball) -Wl,-rpath,"$(PKG_CONFIG_PATH="$pc" pkg-config --variable=libdir superball)"
  "$work/example-pc" > "$work/example-pc.out"
  cmp "$work/example-pc.out" <("$work/example/superball_example")
  "$prefix/bin/superball" solve "$prefix/share/superball/scenes/paper-4.4-alpha2.toml" --precision exact > /dev/null
  [ -s "$prefix/share/man/man1/superball.1" ]
  # The Python module from the prefix only (its libraries too), then the notebook against it.
  local site="$prefix/lib/python3/dist-packages"
  PYTHONDONTWRITEBYTECODE=1 /usr/bin/python3 "$ROOT/tests/python/check_installed.py" "$prefix" "$site" \
    "$prefix/share/superball/scenes/paper-4.4-alpha2.toml"
  PYTHONPATH="$site" SUPERBALL_SCENES="$prefix/share/superball/scenes" PYTHONDONTWRITEBYTECODE=1 \
    /usr/bin/python3 -m pytest -q -p no:cacheprovider "$ROOT/tests/python/test_notebook.py"
  echo "install: examples/cpp built and run against the installed tree (find_package and pkg-config), the Python module and notebook too, $(find "$prefix" -type f | wc -l) files" >> "$summary"
  rm -rf "$work"
}

# package_check: the Debian package of BUILD_DIR (cpack -G DEB), installed with
# apt-get as a user would, its command and CMake package used from /usr (and its
# Python module, when the build has one), then removed again.
package_check() {
  local sudo="" work deb
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  if dpkg-query -W -f='${Status}' superball 2>/dev/null | grep -q "install ok installed"; then
    echo "package: a superball package is installed already; not replacing it" >> "$summary"
    return 0
  fi
  work="$(mktemp -d)"
  (cd "$BUILD_DIR" && cpack -G DEB > "$work/cpack.log")
  deb="$(ls "$BUILD_DIR"/superball_*.deb)"
  dpkg-deb --field "$deb" Package Version Depends
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "$deb" > "$work/apt.log"
  # shellcheck disable=SC2064
  trap "DEBIAN_FRONTEND=noninteractive $sudo apt-get purge -y -q superball > /dev/null; rm -rf '$work' '$summary'" EXIT
  [ "$(dpkg -S /usr/bin/superball)" = "superball: /usr/bin/superball" ]
  /usr/bin/superball solve /usr/share/superball/scenes/paper-4.4-alpha2.toml --precision exact > "$work/solve.out"
  grep -q "^superball: yes" "$work/solve.out"
  [ -s /usr/share/man/man1/superball.1 ]
  if command -v man > /dev/null; then man -w superball > /dev/null; fi
  # find_package(superball) from the system's own paths, no prefix given.
  cmake -S "$ROOT/examples/cpp" -B "$work/example" -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
  cmake --build "$work/example" -j "$(nproc)" > "$work/build.log"
  "$work/example/superball_example" /usr/share/superball/scenes/paper-4.4-alpha2.toml > /dev/null
  local python=""
  # The listing is read whole first: grep -q would close the pipe early and, under pipefail,
  # dpkg-deb's broken pipe would make the test false (the module then never checked).
  local contents
  contents="$(dpkg-deb --contents "$deb")"
  if grep -q "dist-packages/superball/" <<< "$contents"; then
    (cd "$work" && /usr/bin/python3 -c "import superball; print(superball.__file__)" | grep -q "^/usr/lib/python3/dist-packages/")
    python=", Python module imported"
  fi
  DEBIAN_FRONTEND=noninteractive $sudo apt-get purge -y -q superball > /dev/null
  trap 'rm -f "$summary"' EXIT
  echo "package: $(basename "$deb") installed with apt-get, superball solve and examples/cpp (find_package from /usr) run$python, purged" >> "$summary"
  rm -rf "$work"
}

# sanitized_build [--target T]: build-asan, the build of stages 2 and 3: clang++ (faster than g++
# here, stage 2's comment), AddressSanitizer and UndefinedBehaviorSanitizer, the test suite and
# the libFuzzer target.
sanitized_build() {
  BUILD_DIR="$ROOT/build-asan" configure_and_build -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DSUPERBALL_BUILD_TESTS=ON -DSUPERBALL_BUILD_BENCH=OFF -DSUPERBALL_SANITIZE=address,undefined \
    -DSUPERBALL_BUILD_HEADER_TESTS=OFF -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DSUPERBALL_UNITY_TESTS=ON \
    -DSUPERBALL_BUILD_FUZZ=ON "$@"
}

for stage in $STAGES; do
  stage_start=$SECONDS
  case "$stage" in
    1)
      echo "== stage 1: test suite"
      # With the MPI runner: its tests run mpirun -n 2 and -n 3; stage 2 builds without MPI.
      # The test programs are compiled a few sources at a time as one file (SUPERBALL_UNITY_TESTS,
      # tests/CMakeLists.txt), stages 1 and 2: four files of tests/numeric took 78 s of CPU one by
      # one and 54 s as one under stage 2's flags.
      configure_and_build -DSUPERBALL_BUILD_TESTS=ON -DSUPERBALL_BUILD_PYTHON=ON -DPython_EXECUTABLE=/usr/bin/python3 -DSUPERBALL_WITH_MPI=ON \
        -DSUPERBALL_UNITY_TESTS=ON
      run_ctest "$BUILD_DIR" "suite"
      echo "== stage 1: install into a temporary prefix, examples/cpp against it"
      install_check
      echo "== stage 1: the Debian package, installed and removed"
      package_check
      ;;
    2)
      echo "== stage 2: test suite under AddressSanitizer + UndefinedBehaviorSanitizer"
      # Line tables (-g1) are all a sanitizer's report needs, and the headers' compile-alone
      # tests (stage 1) find nothing a sanitizer could: both only cost build time here.
      # -O1, as AddressSanitizer's documentation advises: on 2 cores it built in 611 s
      # against about 1,040 s at -O2.  With g++ this build took 804 s in a fresh clone
      # (ef8382a, 1,611 s of compile jobs), and stage 3 built cases and numeric again with
      # clang (153 s).  clang++ compiles these flags with less CPU, CPU-s per translation unit,
      # g++ against clang++: tests/numeric compute_case_test 56.0 / 30.8, switch_point_test
      # 27.6 / 21.0, cli/reproduce.cpp 49.9 / 38.4, numeric small_solver.cpp 77.4 / 67.4 (94 with
      # libFuzzer's coverage hooks, which cases and numeric carry here so that stage 3 reuses them).
      sanitized_build
      # Every process that loads CLN ends with a leak that tests/lsan.supp suppresses, and matching
      # the suppression started a symbolizer (llvm-symbolizer or addr2line): 0.3 s of CPU in each of
      # the thousands of processes of the suite (test programs, and every superball they start;
      # a sanitized superball took 0.71 s of CPU on a bad scene, 0.42 s without).  So the processes
      # print raw addresses (symbolize=0), and the output goes through clang's asan_symbolize,
      # which names the frames of a report (function, file:line) as they are printed.
      # The tests whose work is repetition of one code path (randomized cross-checks, one check
      # under every spelling, worker count or catalogue variant) run fewer repetitions
      # (SUPERBALL_TEST_SCALE=small, tests/support/scale.hpp), the property tests 200 random
      # scenes (the fewest whose draw meets every coverage check: 100 hold only 5 banded
      # chains of the 6 asked) and 100 extreme scenes; no assertion is dropped.
      # Side by side on 2 cores at load 4: the 69 tests BadSceneCli and OutputOverInput.Every…
      # took 273 s, 161 s with symbolize=0, 88 s with the small scale too; the 68 in-process
      # bad-scene tests 49 s and 23 s.  Fresh clone: the suite 940 s before these changes,
      # 584 s after (863 tests).  ctest -j starts the long tests first (their COST,
      # superball_test_costs in tests/CMakeLists.txt): in the fresh clone of ef8382a (878 tests,
      # 1,099 s of tests on 2 cores) the red-team classes of 21, 16, 13 and 12 s were started last.
      # Distribute.ThreeShards… (clang build): 69.1 CPU-s at the full scale, 51.8 at the small one.
      ASAN_OPTIONS="symbolize=0" SUPERBALL_TEST_SCALE=small SUPERBALL_PROPERTY_SCENES=200 SUPERBALL_EXTREME_SCENES=100 \
        run_ctest "$ROOT/build-asan" "suite under ASan+UBSan" "env PYTHONUNBUFFERED=1 asan_symbolize -d"
      ;;
    3)
      echo "== stage 3: libFuzzer, ${FUZZ_SECONDS} s"
      # fuzz_scene is built in stage 2's folder: after stage 2, its link is all that is left to do.
      sanitized_build --target fuzz_scene
      work="$(mktemp -d)"
      trap 'rm -rf "$work" "$summary"' EXIT
      # New inputs go to the scratch folder; the committed corpus is only read.
      # The seed is fixed (FUZZ_SEED) so that a run is reproducible: a slower
      # machine runs a prefix of the same sequence of inputs.
      status=0
      "$ROOT/build-asan/tests/fuzz/fuzz_scene" "$work" "$ROOT/tests/fuzz/corpus" -dict="$ROOT/tests/fuzz/scene.dict" -seed="$FUZZ_SEED" \
        -max_total_time="$FUZZ_SECONDS" -artifact_prefix="$work/" -print_final_stats=1 > "$work/log" 2>&1 || status=$?
      tail -n 8 "$work/log"
      if [ "$status" -ne 0 ] || ls "$work"/crash-* "$work"/leak-* "$work"/timeout-* >/dev/null 2>&1; then
        echo "fuzzing found a failing input (libFuzzer exit $status, seed $FUZZ_SEED); its report:"
        sed -n '/^fuzz_scene: finding\|^==[0-9]*==\|deadly signal\|^INFO: Running with/,$p' "$work/log" | grep -v "^#[0-9]" | head -n 80
        for f in "$work"/crash-* "$work"/leak-* "$work"/timeout-*; do
          [ -e "$f" ] || continue
          echo "-- input $(basename "$f") ($(wc -c < "$f") bytes), replay: build-asan/tests/fuzz/fuzz_scene FILE"
          head -c 4096 "$f" | cat -v; echo
        done
        exit 1
      fi
      echo "fuzz: ${FUZZ_SECONDS} s without a failing input" >> "$summary"
      ;;
    4)
      echo "== stage 4: red team, ${REDTEAM_SECONDS} s, seed ${REDTEAM_SEED}"
      configure_and_build -DSUPERBALL_BUILD_TESTS=ON --target superball_redteam_tests
      # Known-failing classes (tests/redteam/known-failures.txt) are reported and skipped.
      status=0
      SUPERBALL_REDTEAM_SECONDS="$REDTEAM_SECONDS" SUPERBALL_REDTEAM_SEED="$REDTEAM_SEED" \
        "$BUILD_DIR/tests/redteam/superball_redteam_tests" || status=$?
      if [ "$status" -ne 0 ]; then
        echo "red team: an invariant was violated (seed $REDTEAM_SEED); the report is above"
        exit 1
      fi
      echo "red team: ${REDTEAM_SECONDS} s without a violation outside tests/redteam/known-failures.txt" >> "$summary"
      ;;
    *) echo "unknown stage $stage" >&2; exit 2 ;;
  esac
  echo "stage $stage: $((SECONDS - stage_start)) s" >> "$summary"
done

echo "== summary"
cat "$summary"
# One plain closing line over every ctest stage.
awk '/tests passed/ { for (i = 1; i <= NF; ++i) { if ($i == "failed") f += $(i - 2); if ($i == "of") t += $(i + 1) } }
     END { printf "tests: %d passed, %d failed\n", t - f, f }' "$summary"
