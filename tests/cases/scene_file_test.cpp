// The scene loader on good scenes (the paper's scenes in cases/scenes and the
// files of tests/data/good), and the exact form of its error messages.  The
// catalogue of bad scene files is tests/numeric/bad_scenes_test.cpp.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "superball/cases/scene_file.hpp"

namespace superball {
namespace {

const std::string kScenes = std::string(SUPERBALL_CASES_DIR) + "/scenes/";
const std::string kGood = std::string(SUPERBALL_TEST_DATA_DIR) + "/good/";

const MatrixEntry& entry(const Scene& s, const char* p, const char* q) {
  const MatrixEntry* e = s.find(Pair::parse(p), Pair::parse(q));
  if (!e) throw std::runtime_error(std::string("no entry (") + p + ", " + q + ")");
  return *e;
}

std::string message_of(const std::string& text, const std::string& origin = "scene.toml") {
  try {
    parse_scene(text, origin);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneFile, PaperScene44Alpha2) {
  const Scene s = load_scene(kScenes + "paper-4.4-alpha2.toml");
  EXPECT_EQ(s.origin, kScenes + "paper-4.4-alpha2.toml");
  EXPECT_FALSE(s.title.empty());
  ASSERT_EQ(s.size(), 4);
  // Paper §4.4: m1 = 0.001, m2 = 10, m3 = 15, m4 = 5e6, obstacle at rest, a = 3.13209.
  EXPECT_EQ(s.bodies[0].mass.fraction(), "1/1000");
  EXPECT_EQ(s.bodies[1].mass.fraction(), "10/1");
  EXPECT_EQ(s.bodies[2].mass.fraction(), "15/1");
  EXPECT_EQ(s.bodies[3].mass.fraction(), "5000000/1");
  for (const Body& b : s.bodies) EXPECT_FALSE(b.infinite);
  EXPECT_FALSE(s.bodies[0].velocity.has_value());
  ASSERT_TRUE(s.bodies[3].velocity.has_value());
  EXPECT_TRUE(s.bodies[3].velocity->is_zero());
  ASSERT_TRUE(s.fall_speed.has_value());
  EXPECT_EQ(s.fall_speed->fraction(), "313209/100000");
  EXPECT_FALSE(s.drop_height.has_value());
  // K12 = 7, K13 = 7, K14 = 1500, K23 = 10, K24 = 13, K34 = 10 and the coupling -100 on alpha_2 = (1-2, 1-4).
  EXPECT_EQ(s.entries.size(), 7u);
  EXPECT_EQ(entry(s, "1-2", "1-2").value.fraction(), "7/1");
  EXPECT_EQ(entry(s, "1-3", "1-3").value.fraction(), "7/1");
  EXPECT_EQ(entry(s, "1-4", "1-4").value.fraction(), "1500/1");
  EXPECT_EQ(entry(s, "2-3", "2-3").value.fraction(), "10/1");
  EXPECT_EQ(entry(s, "2-4", "2-4").value.fraction(), "13/1");
  EXPECT_EQ(entry(s, "3-4", "3-4").value.fraction(), "10/1");
  EXPECT_EQ(entry(s, "1-4", "1-2").value.fraction(), "-100/1");
  EXPECT_FALSE(entry(s, "1-2", "1-4").diagonal());
}

TEST(SceneFile, PaperScene44AsPrintedHasAlpha4) {
  const Scene s = load_scene(kScenes + "paper-4.4-as-printed.toml");
  ASSERT_EQ(s.size(), 4);
  EXPECT_EQ(s.entries.size(), 7u);
  // alpha_4 couples 1-4 with 2-3; nothing couples 1-2 with 1-4.
  EXPECT_EQ(entry(s, "2-3", "1-4").value.fraction(), "-100/1");
  EXPECT_EQ(s.find(Pair::parse("1-2"), Pair::parse("1-4")), nullptr);
}

TEST(SceneFile, EveryPaperSceneLoads) {
  int count = 0;
  for (const auto& f : std::filesystem::directory_iterator(kScenes)) {
    if (f.path().extension() != ".toml") continue;
    ++count;
    EXPECT_NO_THROW({
      const Scene s = load_scene(f.path().string());
      EXPECT_GE(s.size(), 2);
    }) << f.path();
  }
  EXPECT_GE(count, 2);
}

TEST(SceneFile, ExactSpellingsAndCouplings) {
  const Scene s = load_scene(kGood + "fractions-and-couplings.toml");
  ASSERT_EQ(s.size(), 5);
  EXPECT_EQ(s.title, "five bodies, exact spellings");
  EXPECT_EQ(s.drop_height->fraction(), "1/2");
  EXPECT_EQ(s.g.fraction(), "981/100");
  EXPECT_EQ(s.bodies[0].mass.fraction(), "1/1000");  // TOML float 1e-3, read as written
  EXPECT_EQ(s.bodies[1].mass.fraction(), "1/3");
  EXPECT_EQ(s.bodies[2].mass.fraction(), "25/10");
  EXPECT_EQ(s.bodies[2].velocity->fraction(), "-29/10");
  EXPECT_EQ(s.bodies[3].velocity->fraction(), "-1/4");
  EXPECT_EQ(s.bodies[3].mass.fraction(), "1000/1");
  EXPECT_TRUE(s.bodies[4].infinite);
  EXPECT_FALSE(s.bodies[3].infinite);
  EXPECT_EQ(s.entries.size(), 6u);
  EXPECT_EQ(entry(s, "2-3", "2-3").value.fraction(), "1/10");
  EXPECT_EQ(entry(s, "4-5", "4-5").value.fraction(), "125/1000");
  EXPECT_EQ(entry(s, "1-5", "1-2").value.fraction(), "-100/1");
  // Stored once with first < second, whatever order the file gives.
  const MatrixEntry& c = entry(s, "2-3", "4-5");
  EXPECT_EQ(c.first, Pair::parse("2-3"));
  EXPECT_EQ(c.second, Pair::parse("4-5"));
  EXPECT_EQ(c.value.fraction(), "-1/20");
  EXPECT_FALSE(s.flight.requested);
}

TEST(SceneFile, InfiniteMassAsTomlFloatAndFlight) {
  const Scene s = load_scene(kGood + "paper-4.4-alpha4-float-inf.toml");
  ASSERT_EQ(s.size(), 4);
  EXPECT_TRUE(s.bodies[3].infinite);
  EXPECT_FALSE(s.bodies[3].velocity.has_value());
  EXPECT_EQ(s.drop_height->fraction(), "5/10");
  EXPECT_TRUE(s.flight.requested);
}

TEST(SceneFile, NoDissipationTable) {
  const Scene s = load_scene(kGood + "two-bodies-no-dissipation.toml");
  ASSERT_EQ(s.size(), 2);
  EXPECT_TRUE(s.entries.empty());
  EXPECT_EQ(s.g.fraction(), "981/100");  // the default
  EXPECT_EQ(s.bodies[1].velocity->fraction(), "1/1");
}

TEST(SceneFile, MessagesNameFileLineColumnAndField) {
  const std::string text =
      "fall_speed = 1\n"
      "[[body]]\n"
      "mass = -2\n"
      "[[body]]\n"
      "mass = 1\n";
  EXPECT_EQ(message_of(text, "dir/x.toml"), "dir/x.toml:3:8: body[1].mass: must be > 0 (got -2)");
  const std::string key =
      "fall_speed = 1\n"
      "[[body]]\n"
      "mass = 2\n"
      "colour = \"red\"\n"
      "[[body]]\n"
      "mass = 1\n";
  const std::string m = message_of(key, "k.toml");
  EXPECT_EQ(m.rfind("k.toml:4:1: body[1].colour: unknown key", 0), 0u) << m;
  EXPECT_NE(m.find("mass, velocity"), std::string::npos) << m;
}

TEST(SceneFile, NumberReasonsCarryNoFunctionName) {
  // The loader turns Number::parse's "Number::parse(): 'x' why" into a field
  // message; the user should read the reason, not a C++ function name.
  const std::string text =
      "fall_speed = 1\n"
      "[[body]]\n"
      "mass = \"1/0\"\n"
      "[[body]]\n"
      "mass = 1\n";
  const std::string m = message_of(text, "f.toml");
  EXPECT_EQ(m.rfind("f.toml:3:8: body[1].mass: ", 0), 0u) << m;
  EXPECT_NE(m.find("zero denominator"), std::string::npos) << m;
  EXPECT_EQ(m.find("parse()"), std::string::npos) << m;
  const std::string pair = message_of("fall_speed = 1\n[[body]]\nmass = 1\n[[body]]\nmass = 1\n[dissipation]\nK = { \"2-1\" = 1 }\n");
  EXPECT_NE(pair.find("dissipation.K.2-1"), std::string::npos) << pair;
  EXPECT_EQ(pair.find("parse()"), std::string::npos) << pair;
}

TEST(SceneFile, ExactNumbersReadAsWritten) {
  // A TOML float is read as spelled, not through a double: 0.1 is 1/10 and
  // 3.141592653589793238462643383279 keeps all its digits.
  const Scene s = parse_scene(
      "fall_speed = 3.141592653589793238462643383279\n"
      "[[body]]\nmass = 0.1\n[[body]]\nmass = 1e-300\n",
      "pi");
  EXPECT_EQ(s.fall_speed->fraction(), "3141592653589793238462643383279/1000000000000000000000000000000");
  EXPECT_EQ(s.bodies[0].mass.fraction(), "1/10");
  EXPECT_EQ(s.bodies[1].mass.denominator, "1" + std::string(300, '0'));
}

TEST(SceneFile, EmptyTablesAndListsOfMAreNoEntries) {
  // K = {}, alpha = {} and coupling = [] all say "no entries": the same scene.
  const std::string head = "fall_speed = 1\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n[dissipation]\n";
  for (const char* d : {"", "K = {}\n", "alpha = {}\n", "coupling = []\n", "K = {}\ncoupling = []\n"}) {
    SCOPED_TRACE(d);
    try {
      const Scene s = parse_scene(head + d, "empty");
      EXPECT_TRUE(s.entries.empty());
    } catch (const InputError& e) {
      ADD_FAILURE() << e.what();
    }
  }
}

TEST(SceneFile, TomlIntegersInEveryBase) {
  // "Numbers may be TOML integers or floats (read exactly as written)":
  // TOML writes integers in hexadecimal, octal and binary too.
  const std::string tail = "\n[[body]]\nmass = \"inf\"\n";
  for (const char* spelling : {"0x10", "0o20", "0b10000", "+16", "1_6"}) {
    SCOPED_TRACE(spelling);
    try {
      const Scene s = parse_scene(std::string("fall_speed = 1\n[[body]]\nmass = ") + spelling + tail, "bases");
      EXPECT_EQ(s.bodies[0].mass.approx(), 16.0);
    } catch (const InputError& e) {
      ADD_FAILURE() << e.what();
    }
  }
}

TEST(SceneFile, MissingFileAndDirectory) {
  const std::string missing = kGood + "no-such-scene.toml";
  try {
    load_scene(missing);
    ADD_FAILURE() << "loaded a missing file";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(missing + ": ", 0), 0u) << e.what();
  }
  try {
    load_scene(kGood);
    ADD_FAILURE() << "loaded a directory";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(kGood, 0), 0u) << e.what();
  }
}


/// Two scenes state the same thing: same title, speeds, bodies and entries of M (in any order), values exactly equal.
void expect_same_scene(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.title, b.title);
  auto value = [](const std::optional<Number>& x) { return x ? x->fraction() : std::string("none"); };
  EXPECT_EQ(value(a.fall_speed), value(b.fall_speed));
  EXPECT_EQ(value(a.drop_height), value(b.drop_height));
  EXPECT_EQ(a.g.fraction(), b.g.fraction());
  ASSERT_EQ(a.size(), b.size());
  for (int k = 0; k < a.size(); ++k) {
    const Body &x = a.bodies[static_cast<std::size_t>(k)], &y = b.bodies[static_cast<std::size_t>(k)];
    EXPECT_EQ(x.infinite, y.infinite) << "body " << k + 1;
    if (!x.infinite) {
      EXPECT_EQ(x.mass.fraction(), y.mass.fraction()) << "body " << k + 1;
    }
    EXPECT_EQ(value(x.velocity), value(y.velocity)) << "body " << k + 1;
  }
  ASSERT_EQ(a.entries.size(), b.entries.size());
  for (const MatrixEntry& e : a.entries) {
    const MatrixEntry* f = b.find(e.first, e.second);
    ASSERT_NE(f, nullptr) << e.first.name() << "/" << e.second.name();
    EXPECT_EQ(e.value.fraction(), f->value.fraction()) << e.first.name() << "/" << e.second.name();
  }
  EXPECT_EQ(a.flight.requested, b.flight.requested);
  EXPECT_EQ(a.flight.duration.has_value(), b.flight.duration.has_value());
}

TEST(SceneFile, WriteSceneReadsBackTheSameScene) {
  int files = 0;
  for (const std::string& dir : {kScenes, kGood})
    for (const auto& f : std::filesystem::directory_iterator(dir)) {
      if (f.path().extension() != ".toml") continue;
      ++files;
      SCOPED_TRACE(f.path().string());
      const Scene s = load_scene(f.path().string());
      const std::string text = write_scene(s, "written back\nby the test");
      EXPECT_EQ(text.rfind("# written back\n# by the test\n", 0), 0u);
      expect_same_scene(s, parse_scene(text, "written.toml"));
    }
  EXPECT_GE(files, 10);
}

TEST(SceneFile, WriteSceneKeepsExactFractionsAndCouplings) {
  Scene s = parse_scene(
      "title = \"a \\\"quoted\\\" title\"\n"
      "drop_height = \"1/3\"\ng = 10\n"
      "[[body]]\nmass = \"2/7\"\n[[body]]\nmass = 1e-3\n[[body]]\nmass = \"inf\"\n"
      "[dissipation]\nK = { \"1-2\" = 3, \"1-3\" = 0x10 }\n"
      "coupling = [ { pairs = [\"1-2\", \"1-3\"], value = \"-5/2\" } ]\n[flight]\nduration = 2\n",
      "fractions.toml");
  const std::string text = write_scene(s);
  EXPECT_NE(text.find("\"2/7\""), std::string::npos) << text;
  EXPECT_NE(text.find("mass = 1e-3"), std::string::npos) << text;
  EXPECT_NE(text.find("\"1-3\" = 16"), std::string::npos) << text;  // a TOML hex integer is written in decimal
  expect_same_scene(s, parse_scene(text, "written.toml"));
}

}  // namespace
}  // namespace superball
