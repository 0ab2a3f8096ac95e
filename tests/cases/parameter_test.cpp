// Parameter names (`--vary KEY`): parsing against a scene and setting values.
#include <gtest/gtest.h>

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "superball/cases/parameter.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/cases/vocabulary.hpp"

namespace superball {
namespace {

const char* const kFourBodies = R"(
fall_speed = 2
[[body]]
mass = 1
[[body]]
mass = 2
[[body]]
mass = 3
[[body]]
mass = "inf"
[dissipation]
K = { "1-2" = 7, "1-4" = 1500, "3-4" = 10 }
alpha = { "2" = -100 }
)";

const char* const kThreeBodies = R"(
drop_height = 0.5
[[body]]
mass = 1
[[body]]
mass = 2
[[body]]
mass = 3
velocity = 0
)";

TEST(Parameter, SetsAnExistingEntryOfM) {
  Scene s = parse_scene(kFourBodies, "four");
  const std::size_t entries = s.entries.size();
  Parameter::parse("K.3-4", s).set(s, Number::parse("12.5"));
  EXPECT_EQ(s.entries.size(), entries);
  EXPECT_EQ(s.find(Pair::parse("3-4"), Pair::parse("3-4"))->value.text, "12.5");
  // alpha.2 and coupling.1-4/1-2 name the same entry as the file's alpha 2.
  Parameter::parse("coupling.1-4/1-2", s).set(s, Number::parse("-50"));
  EXPECT_EQ(s.entries.size(), entries);
  EXPECT_EQ(s.find(Pair::parse("1-2"), Pair::parse("1-4"))->value.text, "-50");
  Parameter::parse("alpha.2", s).set(s, Number::parse("-60"));
  EXPECT_EQ(s.entries.size(), entries);
  EXPECT_EQ(s.find(Pair::parse("1-4"), Pair::parse("1-2"))->value.text, "-60");
}

TEST(Parameter, AddsAnAbsentEntry) {
  Scene s = parse_scene(kFourBodies, "four");
  const std::size_t entries = s.entries.size();
  Parameter::parse("K.2-3", s).set(s, Number::parse("1/3"));
  ASSERT_EQ(s.entries.size(), entries + 1);
  EXPECT_EQ(s.find(Pair::parse("2-3"), Pair::parse("2-3"))->value.fraction(), "1/3");
  Parameter::parse("alpha.4", s).set(s, Number::parse("-1"));
  ASSERT_EQ(s.entries.size(), entries + 2);
  EXPECT_NE(s.find(Pair::parse("1-4"), Pair::parse("2-3")), nullptr);
}

TEST(Parameter, SetsBodiesAndTheFall) {
  Scene s = parse_scene(kFourBodies, "four");
  Parameter::parse("mass.1", s).set(s, Number::parse("0.001"));
  EXPECT_EQ(s.bodies[0].mass.fraction(), "1/1000");
  Parameter::parse("velocity.4", s).set(s, Number::parse("-1"));
  ASSERT_TRUE(s.bodies[3].velocity.has_value());
  EXPECT_EQ(s.bodies[3].velocity->fraction(), "-1/1");
  Parameter::parse("fall_speed", s).set(s, Number::parse("3"));
  EXPECT_EQ(s.fall_speed->text, "3");
  Parameter::parse("g", s).set(s, Number::parse("10"));
  EXPECT_EQ(s.g.text, "10");
  Scene t = parse_scene(kThreeBodies, "three");
  Parameter::parse("drop_height", t).set(t, Number::parse("2"));
  EXPECT_EQ(t.drop_height->text, "2");
  EXPECT_EQ(Parameter::parse("K.1-2", t).key(), "K.1-2");
}

// Parameter::set() applies the scene loader's checks: a value a scene file
// could not hold is refused with the key and the value, and the scene is left
// as it was.
TEST(Parameter, RefusesWhatTheLoaderRefuses) {
  const Scene four = parse_scene(kFourBodies, "four"), three = parse_scene(kThreeBodies, "three");
  struct Bad {
    const Scene& scene;
    const char* key;
    const char* value;
    const char* why;  // the loader's words
  };
  const Bad bad[] = {{four, "g", "-1", "g: must be > 0 (got -1)"},
                     {four, "g", "0", "g: must be > 0"},
                     {three, "drop_height", "-1/2", "drop_height: must be >= 0"},
                     {four, "fall_speed", "-1", "fall_speed: must be >= 0"},
                     {four, "mass.1", "0", "body[1].mass: must be > 0"},
                     {three, "mass.3", "-2", "body[3].mass: must be > 0"}};
  for (const Bad& b : bad) {
    Scene s = b.scene;
    const Parameter p = Parameter::parse(b.key, s);
    try {
      p.set(s, Number::parse(b.value));
      ADD_FAILURE() << b.key << " = " << b.value << " accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what, s.origin + ": " + b.key + " = " + b.value + ": " + what.substr(what.find(b.why))) << what;
      EXPECT_NE(what.find(b.why), std::string::npos) << what;
    }
    EXPECT_EQ(write_scene(s), write_scene(b.scene)) << "the scene changed";
  }
  // The edges the loader admits are admitted.
  Scene s = three;
  Parameter::parse("drop_height", s).set(s, Number::parse("0"));
  Parameter::parse("mass.1", s).set(s, Number::parse("1/1000000000"));
  Parameter::parse("g", s).set(s, Number::parse("1e-9"));
  EXPECT_EQ(s.drop_height->text, "0");
  Scene f = four;
  Parameter::parse("fall_speed", f).set(f, Number::parse("0"));
  EXPECT_EQ(f.fall_speed->text, "0");
}

struct BadKey {
  const char* key;
  const char* reason;  // substring of the message
};

class ParameterBad : public ::testing::TestWithParam<BadKey> {};

TEST_P(ParameterBad, IsRejectedWithTheFunctionPrefix) {
  const Scene four = parse_scene(kFourBodies, "four");
  const BadKey b = GetParam();
  try {
    Parameter::parse(b.key, four);
    ADD_FAILURE() << "'" << b.key << "' accepted";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("Parameter::parse(): '" + std::string(b.key) + "': ", 0), 0u) << what;
    EXPECT_NE(what.find(b.reason), std::string::npos) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(Keys, ParameterBad,
                         ::testing::Values(BadKey{"K.4-5", "outside bodies 1..4"}, BadKey{"K.2-1", "not a pair"},
                                           BadKey{"K", "not a pair"}, BadKey{"alpha.8", "alpha must be 1..7"},
                                           BadKey{"alpha.0", "alpha must be 1..7"}, BadKey{"alpha.12", "alpha must be"},
                                           BadKey{"coupling.1-2", "coupling.i-j/k-l"},
                                           BadKey{"coupling.1-2/1-2", "two different pairs"},
                                           BadKey{"coupling.1-2/1-5", "outside bodies"}, BadKey{"mass.0", "body must be 1..4"},
                                           BadKey{"mass.5", "body must be 1..4"}, BadKey{"mass.x", "body must be"},
                                           BadKey{"mass.1x", "body must be"}, BadKey{"mass.4", "fixed obstacle"},
                                           BadKey{"velocity.9", "body must be"}, BadKey{"drop_height", "fall_speed"},
                                           BadKey{"speed", "unknown parameter"}, BadKey{"", "unknown parameter"},
                                           BadKey{"gap.1", "no [drop] table"}));

TEST(Parameter, GapIsABodysReleaseDistanceInADropScene) {
  const Scene drop = parse_scene("drop_height = 1\n[[body]]\nmass = 1\ngap = 0.5\n[[body]]\nmass = 2\n[[body]]\nmass = 3\n"
                                 "[[body]]\nmass = \"inf\"\n[dissipation]\nK = { \"1-2\" = 1, \"2-3\" = 1, \"3-4\" = 1 }\n[drop]\n",
                                 "drop");
  const Parameter gap = Parameter::parse("gap.01", drop);
  EXPECT_EQ(gap.key(), "gap.1");
  EXPECT_EQ(gap, Parameter::parse("gap.1", drop));
  EXPECT_NE(Parameter::parse("gap.2", drop), gap);
  Scene s = drop;
  gap.set(s, Number::parse("1/4"));
  ASSERT_TRUE(s.bodies[0].gap);
  EXPECT_EQ(s.bodies[0].gap->text, "1/4");
  // The loader's check: a gap is >= 0; the scene is left as it was.
  try {
    gap.set(s, Number::parse("-1"));
    ADD_FAILURE() << "a negative gap was set";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "drop: gap.1 = -1: body[1].gap: must be >= 0 m (got -1)");
  }
  EXPECT_EQ(s.bodies[0].gap->text, "1/4");
  // Body 3's distance to the obstacle is drop_height, and the obstacle has none below it.
  for (const char* key : {"gap.3", "gap.4", "gap.0", "gap.x"}) EXPECT_THROW(Parameter::parse(key, drop), std::invalid_argument) << key;
}

TEST(Parameter, AlphaNeedsFourBodies) {
  const Scene three = parse_scene(kThreeBodies, "three");
  try {
    Parameter::parse("alpha.1", three);
    ADD_FAILURE() << "alpha accepted for 3 bodies";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("4 bodies"), std::string::npos) << e.what();
  }
  EXPECT_THROW(Parameter::parse("fall_speed", three), std::invalid_argument);
}

/// A scene of \p n bodies of finite mass, falling at 1, with no entry of M.
Scene falling(int n) {
  std::string text = "fall_speed = 1\n";
  for (int i = 0; i < n; ++i) text += "[[body]]\nmass = " + std::to_string(i + 1) + "\n";
  return parse_scene(text, "n" + std::to_string(n));
}

/// Spellings of the index \p i: as is and with a leading zero.
std::vector<std::string> index_spellings(int i) {
  const std::string d = std::to_string(i);
  return {d, "0" + d};
}

/// Every spelling of the pair p-q (each index as index_spellings()).
std::vector<std::string> pair_spellings(const Pair& p) {
  std::vector<std::string> out;
  for (const std::string& i : index_spellings(p.i))
    for (const std::string& j : index_spellings(p.j)) out.push_back(i + "-" + j);
  return out;
}

/// The parameters of a scene of \p n bodies, each with every one of its
/// spellings: K.i-j, coupling.i-j/k-l (both orders), alpha.k (n = 4),
/// mass.i, velocity.i, with leading zeros on the indices; and the canonical
/// key each must have.
std::map<std::string, std::vector<std::string>> spellings(int n) {
  std::vector<Pair> pairs;
  for (int i = 1; i <= n; ++i)
    for (int j = i + 1; j <= n; ++j) pairs.push_back({i, j});
  std::map<std::string, std::vector<std::string>> out;
  for (const Pair& p : pairs)
    for (const std::string& s : pair_spellings(p)) out["K." + p.name()].push_back("K." + s);
  const Vocabulary& v = Vocabulary::paper();
  for (std::size_t a = 0; a < pairs.size(); ++a)
    for (std::size_t b = a + 1; b < pairs.size(); ++b) {
      const Pair &p = pairs[a], &q = pairs[b];
      const auto alpha = n == v.bodies() ? v.alpha_index(p, q) : std::nullopt;
      std::vector<std::string>& names = out[alpha ? "alpha." + std::to_string(*alpha) : "coupling." + p.name() + "/" + q.name()];
      for (const std::string& x : pair_spellings(p))
        for (const std::string& y : pair_spellings(q)) {
          names.push_back("coupling." + x + "/" + y);
          names.push_back("coupling." + y + "/" + x);
        }
      if (alpha)
        for (const std::string& k : index_spellings(*alpha)) names.push_back("alpha." + k);
    }
  for (int i = 1; i <= n; ++i)
    for (const std::string& k : index_spellings(i)) {
      out["mass." + std::to_string(i)].push_back("mass." + k);
      out["velocity." + std::to_string(i)].push_back("velocity." + k);
    }
  for (const char* name : {"fall_speed", "g"}) out[name].push_back(name);
  return out;
}

// One parameter, one name: every spelling of an entry parses into the same
// Parameter, with the canonical key and the spelling given (every pair of
// spellings of every parameter compared), and two different entries never
// compare equal (each entry's first and last spelling against every other
// entry's).  n = 2..8, alpha.k at n = 4.
TEST(Parameter, EverySpellingOfAnEntryIsOneParameter) {
  for (int n = 2; n <= 8; ++n) {
    const Scene scene = falling(n);
    std::vector<std::vector<Parameter>> entries;
    for (const auto& [key, spelled] : spellings(n)) {
      std::vector<Parameter> parsed;
      for (const std::string& s : spelled) {
        parsed.push_back(Parameter::parse(s, scene));
        EXPECT_EQ(parsed.back().key(), key) << "n = " << n << ", " << s;
        EXPECT_EQ(parsed.back().spelling(), s);
      }
      for (const Parameter& a : parsed)
        for (const Parameter& b : parsed)
          if (a != b || !(a == b)) ADD_FAILURE() << "n = " << n << ": " << a.spelling() << " and " << b.spelling() << " differ";
      entries.push_back(std::move(parsed));
    }
    for (std::size_t i = 0; i < entries.size(); ++i)
      for (std::size_t j = 0; j < entries.size(); ++j)
        for (const Parameter* a : {&entries[i].front(), &entries[i].back()})
          for (const Parameter* b : {&entries[j].front(), &entries[j].back()})
            if ((*a == *b) != (i == j)) ADD_FAILURE() << "n = " << n << ": " << a->spelling() << " and " << b->spelling();
    // Every entry of M, body and fall parameter: n(n-1)/2 K's, C(n(n-1)/2, 2) couplings, 2n, fall_speed and g.
    const std::size_t pairs = static_cast<std::size_t>(n * (n - 1) / 2);
    EXPECT_EQ(entries.size(), pairs + pairs * (pairs - 1) / 2 + 2 * static_cast<std::size_t>(n) + 2) << "n = " << n;
  }
}

// The issue's spellings of one entry at n = 4, and set() through each
// reaching the one entry of the scene.
TEST(Parameter, PaperSpellingsNameOneEntry) {
  Scene s = parse_scene(kFourBodies, "four");
  EXPECT_EQ(Parameter::parse("K.03-4", s), Parameter::parse("K.3-4", s));
  EXPECT_EQ(Parameter::parse("K.03-4", s).key(), "K.3-4");
  EXPECT_EQ(Parameter::parse("alpha.2", s), Parameter::parse("coupling.1-2/1-4", s));
  EXPECT_EQ(Parameter::parse("coupling.1-4/1-2", s), Parameter::parse("coupling.1-2/1-4", s));
  EXPECT_EQ(Parameter::parse("coupling.1-4/1-2", s).key(), "alpha.2");
  EXPECT_EQ(Parameter::parse("mass.01", s), Parameter::parse("mass.1", s));
  EXPECT_NE(Parameter::parse("mass.1", s), Parameter::parse("velocity.1", s));
  EXPECT_NE(Parameter::parse("K.1-2", s), Parameter::parse("K.1-3", s));
  EXPECT_NE(Parameter::parse("alpha.2", s), Parameter::parse("alpha.3", s));
  const std::size_t entries = s.entries.size();
  Parameter::parse("K.03-04", s).set(s, Number::parse("11"));
  Parameter::parse("coupling.01-4/1-02", s).set(s, Number::parse("-70"));
  EXPECT_EQ(s.entries.size(), entries);
  EXPECT_EQ(s.find(Pair::parse("3-4"), Pair::parse("3-4"))->value.text, "11");
  EXPECT_EQ(s.find(Pair::parse("1-2"), Pair::parse("1-4"))->value.text, "-70");
  // A coupling the paper does not name keeps the coupling spelling, pairs in order.
  EXPECT_EQ(Parameter::parse("coupling.2-3/1-2", s).key(), "coupling.1-2/2-3");
}

// A value past 64 bits is an exact number like any other: set() writes the
// scene and reads it back (issue 25: 1e19 was "not representable in 64 bits").
TEST(Parameter, SetsValuesPastSixtyFourBits) {
  Scene s = parse_scene(kFourBodies, "four");
  for (const char* big : {"10000000000000000000", "-10000000000000000000/3", "1" "000000000000000000000000000000000000000000"}) {
    Parameter::parse(std::string(big).front() == '-' ? "alpha.2" : "K.1-4", s).set(s, Number::parse(big));
    const Scene back = parse_scene(write_scene(s), "back");
    EXPECT_EQ(write_scene(back), write_scene(s)) << big;
  }
  EXPECT_EQ(s.find(Pair::parse("1-4"), Pair::parse("1-4"))->value.fraction(), "1000000000000000000000000000000000000000000/1");
  EXPECT_EQ(s.find(Pair::parse("1-2"), Pair::parse("1-4"))->value.fraction(), "-10000000000000000000/3");
}

// Spellings that are not indices stay refused (no sign, space or other digits).
TEST(Parameter, IndicesAreDecimalDigitsOnly) {
  const Scene four = parse_scene(kFourBodies, "four");
  for (const char* key : {"mass.+1", "mass. 1", "mass.1 ", "mass.-1", "velocity.0x1", "alpha.+2", "alpha. 2", "alpha.2.0", "K.+3-4",
                          "K. 3-4", "coupling.1-2/ 1-4", "mass.0000000001", "mass."})
    EXPECT_THROW(Parameter::parse(key, four), std::invalid_argument) << key;
}

}  // namespace
}  // namespace superball
