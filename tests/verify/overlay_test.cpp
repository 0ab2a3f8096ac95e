// The overlay of a map (issue 15): on the paper's two planes, every boundary
// point the exact solutions gave lies within the brackets' widths of a zero
// of a derived condition of a case on its sides, each zero really separates
// the two sides of its condition, and keys the derivation cannot follow are
// refused.
#include <gtest/gtest.h>

#include <string>

#include "superball/cases/parameter.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/numeric/map.hpp"
#include "superball/verify/overlay.hpp"
#include "superball/verify/space.hpp"

namespace superball::verify {
namespace {

const std::string kScenes = std::string(SUPERBALL_CASES_DIR) + "/scenes/";

numeric::Map map_of(const Scene& scene, const std::string& x, const cln::cl_RA& x0, const cln::cl_RA& x1, const std::string& y,
                    const cln::cl_RA& y0, const cln::cl_RA& y1, int steps) {
  numeric::MapSettings settings;
  settings.threads = 2;
  return numeric::map(scene, {Parameter::parse(x, scene), x0, x1, steps}, {Parameter::parse(y, scene), y0, y1, steps}, settings);
}

void expect_agreement(const Scene& scene, const numeric::Map& m) {
  const Overlay o = overlay(scene, m);
  EXPECT_FALSE(o.cases.empty());
  EXPECT_GT(o.conditions, 0);
  std::size_t compared = 0;
  for (const numeric::MapBoundary& b : m.boundaries) compared += b.below_psd && b.above_psd;
  ASSERT_EQ(o.matches.size(), compared);
  ASSERT_GT(compared, 0u);
  for (const OverlayMatch& match : o.matches) {
    const auto [x, y] = numeric::position(m, m.boundaries[match.boundary]);
    EXPECT_TRUE(match.found) << "no derived zero next to (" << x << ", " << y << ")";
    EXPECT_TRUE(match.agrees()) << "at (" << x << ", " << y << "): distance " << cln::double_approx(match.distance) << ", allowed "
                                << cln::double_approx(match.allowed);
  }
  EXPECT_TRUE(o.agrees());
  EXPECT_LE(o.largest_distance, o.largest_allowed);
  EXPECT_LE(o.largest_allowed, 2 * 0x1p-64 * 1.0001);  // two brackets of 2^-64 of the step
  for (const DerivedZero& z : o.zeros) EXPECT_TRUE(z.low < z.high);
}

TEST(Overlay, TheDerivedBoundariesOfTheK34Alpha2PlaneAreTheExactOnes) {
  const Scene scene = load_scene(kScenes + "paper-4.4-alpha2.toml");
  expect_agreement(scene, map_of(scene, "K.3-4", 0, 20, "alpha.2", -150, 0, 17));
}

TEST(Overlay, TheDerivedBoundariesOfTheAlpha2Alpha5PlaneAreTheExactOnes) {
  // α₅ is not in the scene: the map adds it, and so does the overlay's pattern.
  const Scene scene = load_scene(kScenes + "paper-fig5-alpha2.toml");
  expect_agreement(scene, map_of(scene, "alpha.2", -200, 100, "alpha.5", -10, 10, 13));
}

TEST(Overlay, TheSceneOfABoundaryPointIsAtTheMiddleOfItsBracket) {
  // What --out writes for a disagreement: the scene at the boundary point, the other parameter at its grid value.
  const Scene scene = load_scene(kScenes + "paper-4.4-alpha2.toml");
  const numeric::Map m = map_of(scene, "K.3-4", 0, 20, "alpha.2", -150, 0, 5);
  const Overlay o = overlay(scene, m);
  ASSERT_FALSE(o.matches.empty());
  for (const OverlayMatch& match : o.matches) {
    const numeric::MapBoundary& b = m.boundaries[match.boundary];
    const Scene at = o.scene_at(scene, m, match);
    const cln::cl_RA mid = (b.low + b.high) / 2;
    const cln::cl_RA x = b.along_x ? mid : m.x.values()[static_cast<std::size_t>(b.i)];
    const cln::cl_RA y = b.along_x ? m.y.values()[static_cast<std::size_t>(b.j)] : mid;
    const Scene expected = numeric::with_value(numeric::with_value(scene, m.x.parameter, x), m.y.parameter, y);
    EXPECT_EQ(write_scene(at), write_scene(expected));
  }
}

TEST(Overlay, KeysTheDerivationCannotFollowAreRefused) {
  const Scene scene = load_scene(kScenes + "paper-4.4-alpha2.toml");
  const numeric::Map m = map_of(scene, "K.3-4", 0, 20, "g", 1, 10, 3);
  try {
    (void)overlay(scene, m);
    ADD_FAILURE() << "not refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("g: the derivation's coordinates are not affine in it"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace superball::verify
