// Parameter names (`--vary KEY`): parsing against a scene and setting values.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "superball/cases/parameter.hpp"
#include "superball/cases/scene_file.hpp"

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
                                           BadKey{"speed", "unknown parameter"}, BadKey{"", "unknown parameter"}));

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

}  // namespace
}  // namespace superball
