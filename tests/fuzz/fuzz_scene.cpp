// libFuzzer target over scene parsing and solving (issues 6 and 12).  Any
// input must end in a clean InputError or a solution that passes the physical
// checks; a crash, a sanitizer report or a failed check is a finding.
//
// A line `#vary KEY=VALUE` (a TOML comment, so the scene still parses) sets a
// parameter as `sweep --vary` does (K.i-j, alpha.k, coupling.i-j/k-l, mass.i,
// velocity.i, drop_height, fall_speed, g) before the solves; the sweep's
// double point must then be finite whenever its status is success.
// scene.dict holds the tokens libFuzzer splices in: extreme exponents
// (1e400, 1e-320, ...), inf/nan spellings, underscores, a byte-order mark,
// deep dotted keys and the sweep keys.
//
// Build (clang): cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DSUPERBALL_BUILD_FUZZ=ON
// Run:           build-fuzz/tests/fuzz/fuzz_scene tests/fuzz/corpus -dict=tests/fuzz/scene.dict -max_total_time=60
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>

#include "superball/cases/parameter.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/numeric/collision.hpp"
#include "superball/numeric/sweep.hpp"

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

/// The `#vary KEY=VALUE` line of \p text, if any.
std::optional<std::pair<std::string, std::string>> vary_line(const std::string& text) {
  const std::string tag = "#vary ";
  const auto at = text.find(tag);
  if (at == std::string::npos || (at > 0 && text[at - 1] != '\n')) return std::nullopt;
  const auto end = text.find('\n', at);
  const std::string line = text.substr(at + tag.size(), end == std::string::npos ? std::string::npos : end - at - tag.size());
  const auto eq = line.find('=');
  if (eq == std::string::npos) return std::nullopt;
  return std::make_pair(line.substr(0, eq), line.substr(eq + 1));
}

/// \p scene with the parameter of \p vary set as `sweep --vary` sets it, after
/// checking the sweep's double point: a success must be finite.  Nothing when
/// the key or the value is refused (std::invalid_argument, as the command).
std::optional<Scene> varied(const Scene& scene, const std::pair<std::string, std::string>& vary) {
  try {
    const Parameter parameter = Parameter::parse(vary.first, scene);
    const cln::cl_RA value = numeric::parse_rational(Number::parse(vary.second).fraction());
    const auto points = numeric::sweep(scene, parameter, {value}, numeric::Precision::parse("double"));
    for (const auto& p : points)
      if (p.status == numeric::Status::Success)
        for (double u : p.velocities_after)
          if (!std::isfinite(u)) finding("sweep point with status success and a non-finite velocity");
    return numeric::with_value(scene, parameter, value);
  } catch (const std::invalid_argument&) {
    return std::nullopt;  // refused as the command refuses it (exit 2)
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 4096) return 0;  // scenes are small; keep the exact solves fast
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    Scene scene = parse_scene(text, "fuzz.toml");
    if (scene.size() > 12) return 0;
    if (const auto vary = vary_line(text)) {
      auto v = varied(scene, *vary);
      if (!v) return 0;
      scene = std::move(*v);
    }
    const auto exact_scene = numeric::ExactScene::from(scene);
    if (!exact_scene.exact_u()) return 0;  // irrational velocities: exact arithmetic does not apply
    const auto d = numeric::solve(numeric::Problem<double>::from(exact_scene));
    if (d.status == numeric::Status::Success)
      for (double u : d.velocities_after)
        if (!std::isfinite(u)) finding("double solve with status success and a non-finite velocity");
    check(exact_scene);
  } catch (const InputError&) {
    // the expected outcome for malformed input
  }
  return 0;
}
