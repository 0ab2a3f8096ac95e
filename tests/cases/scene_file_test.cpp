// The scene loader on good scenes (the paper's scenes in cases/scenes and the
// files of tests/data/good), and the exact form of its error messages.  The
// catalogue of bad scene files is tests/numeric/bad_scenes_test.cpp.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <thread>

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
    EXPECT_NE(std::string(e.what()).find("is a directory"), std::string::npos) << e.what();
  }
}

const std::string kTwoBodies = "[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n";
const std::string kBom = "\xEF\xBB\xBF";
const std::string kTooDeep =
    ": tables, arrays and dotted keys nest deeper than " + std::to_string(max_scene_nesting) + " levels (a scene needs a few)";

/// The message of loading \p path, "" when it loads.
std::string load_message(const std::string& path) {
  try {
    load_scene(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

/// A folder of its own for one test, removed with what it holds.
class TemporaryDirectory {
 public:
  TemporaryDirectory() {
    std::string pattern = ::testing::TempDir() + "superball-scene-XXXXXX";
    if (!::mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TemporaryDirectory() { std::filesystem::remove_all(path_); }
  std::string operator/(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

void write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

TEST(SceneFile, ByteOrderMarkIsSkipped) {
  // The exact text of a value is sliced from the source by line and column;
  // a mark counted on one side only read "fall_speed =    1.5e3" as 1 and
  // refused "g = 2.5".
  const Scene a = parse_scene(kBom + "fall_speed =    1.5e3\n" + kTwoBodies, "bom.toml");
  EXPECT_EQ(a.fall_speed->fraction(), "1500/1");
  const Scene b = parse_scene(kBom + "g = 2.5\nfall_speed = 1\n" + kTwoBodies, "bom.toml");
  EXPECT_EQ(b.g.fraction(), "25/10");
  // Places in messages are the same with and without the mark.
  EXPECT_EQ(message_of(kBom + "fall_speed = -1.5e3\n" + kTwoBodies),
            "scene.toml:1:14: fall_speed: must be >= 0 (a speed; bodies fall at -fall_speed)");
  // And from a file.
  TemporaryDirectory dir;
  write_file(dir / "bom.toml", kBom + "drop_height = 0.5\n" + kTwoBodies);
  EXPECT_EQ(load_scene(dir / "bom.toml").drop_height->fraction(), "5/10");
}

TEST(SceneFile, ColumnsCountCodePointsTabsAndCrLf) {
  // toml++ counts columns in code points: 'é' (two bytes) is one column, a tab
  // is one.  The spelling of a value after them on the same line is exact.
  // (Keys are read in byte order: K.1-2 before the unknown pair "éé".)
  const std::string m = message_of("fall_speed = 1\n" + kTwoBodies + "[dissipation]\nK = { \"\xC3\xA9\xC3\xA9\" = 1, \"1-2\" = nan }\n");
  EXPECT_EQ(m, "scene.toml:7:25: dissipation.K.1-2: must be a finite number (got nan)") << m;
  const Scene t = parse_scene("fall_speed =\t\t1.5e3\t# tabs\n" + kTwoBodies, "tabs.toml");
  EXPECT_EQ(t.fall_speed->fraction(), "1500/1");
  const Scene c = parse_scene(kBom + "fall_speed = 2.5\r\n[[body]]\r\nmass = 1.25e-3\r\n[[body]]\r\nmass = +inf\r\n", "crlf.toml");
  EXPECT_EQ(c.fall_speed->fraction(), "25/10");
  EXPECT_EQ(c.bodies[0].mass.fraction(), "125/100000");
  EXPECT_TRUE(c.bodies[1].infinite);
}

TEST(SceneFile, PlusInfIsInfLikeInf) {
  for (const char* spelling : {"inf", "+inf", "\"inf\"", "\"+inf\""}) {
    SCOPED_TRACE(spelling);
    const Scene s = parse_scene(std::string("fall_speed = 1\n[[body]]\nmass = 1\n[[body]]\nmass = ") + spelling + "\n", "inf.toml");
    EXPECT_TRUE(s.bodies[1].infinite);
    const std::string m = message_of(std::string("fall_speed = 1\n[[body]]\nmass = ") + spelling + "\n[[body]]\nmass = 1\n");
    EXPECT_NE(m.find("only the bottom body may have infinite mass"), std::string::npos) << m;
  }
  // Nothing else new: -inf and other strings stay refused.
  for (const char* spelling : {"-inf", "\"-inf\"", "\" inf\"", "\"++inf\"", "\"Inf\""}) {
    SCOPED_TRACE(spelling);
    EXPECT_FALSE(message_of(std::string("fall_speed = 1\n[[body]]\nmass = 1\n[[body]]\nmass = ") + spelling + "\n").empty());
  }
}

TEST(SceneFile, UnderscoresOnlyBetweenDigits) {
  const std::string m = message_of("fall_speed = 1\n[[body]]\nmass = \"_1_\"\n[[body]]\nmass = 1\n");
  EXPECT_EQ(m, "scene.toml:3:8: body[1].mass: '_1_' has an '_' that is not between two digits") << m;
  EXPECT_EQ(parse_scene("fall_speed = 1\n[[body]]\nmass = \"1_000\"\n" + kTwoBodies, "ok").bodies[0].mass.fraction(), "1000/1");
}

TEST(SceneFile, ControlCharactersInMessagesAreEscaped) {
  // A key or value echoed back keeps the message on one line, prints no raw
  // control byte, and a NUL does not cut it short.
  const std::string head = "fall_speed = 1\n[[body]]\nmass = 1\n";
  struct Case {
    const char* key;      // as written in TOML
    const char* printed;  // as the message shows it
  };
  for (const Case c : {Case{R"(a\u0000b)", R"(a\0b)"}, Case{R"(a\nb)", R"(a\nb)"}, Case{R"(a\u001b[2Jb)", R"(a\e[2Jb)"},
                       Case{R"(a\u007fb)", R"(a\x7fb)"}, Case{R"(a\u0001b\tc\rd)", R"(a\x01b\tc\rd)"}, Case{R"(a\u009bb)", R"(a\u009bb)"}}) {
    SCOPED_TRACE(c.key);
    const std::string m = message_of(head + "\"" + c.key + "\" = 2\n" + kTwoBodies);
    EXPECT_NE(m.find(std::string("body[1].") + c.printed + ": unknown key (expected one of: gap, mass, velocity)"), std::string::npos) << m;
    for (const char ch : m) EXPECT_TRUE(static_cast<unsigned char>(ch) >= 0x20 && ch != 0x7f) << int(ch) << " in " << m;
    EXPECT_EQ(m.find("\xC2\x9B"), std::string::npos) << m;
  }
  const std::string v = message_of("fall_speed = 1\n[[body]]\nmass = \"1\\u001b[31m\"\n" + kTwoBodies);
  EXPECT_EQ(v, R"(scene.toml:3:8: body[1].mass: '1\e[31m' is not a number (unexpected '\e'))") << v;
  EXPECT_EQ(printable(std::string("x\0y\x1b\x7f\n\xC3\xA9", 8)), std::string(R"(x\0y\e\x7f\n)") + "\xC3\xA9");
}

std::string repeat(const std::string& s, int n) {
  std::string out;
  for (int k = 0; k < n; ++k) out += s;
  return out;
}

TEST(SceneFile, NestingIsLimitedBeforeParsing) {
  // 50,000 levels crashed the TOML parser (it recurses once per level); each
  // kind of nesting is refused by the pre-scan with the line, no crash.
  const int deep = 50000;
  const std::string dotted = "a" + repeat(".a", deep - 1);
  struct Case {
    std::string name, text;
    int line;
  };
  for (const Case& c : {Case{"dotted key", "fall_speed = 1\n" + dotted + " = 1\n", 2}, Case{"table header", "\n\n[" + dotted + "]\n", 3},
                        Case{"array of tables header", "[[" + dotted + "]]\n", 1},
                        Case{"quoted dotted key", repeat("\"a\" . ", deep) + "a = 1\n", 1},
                        Case{"inline tables", "x = " + repeat("{a=", deep) + "1" + repeat("}", deep) + "\n", 1},
                        Case{"arrays", "x = " + repeat("[", deep) + repeat("]", deep) + "\n", 1},
                        Case{"arrays over lines", "x = [\n" + repeat("[\n", deep), max_scene_nesting},
                        Case{"dotted keys in inline tables", "x = " + repeat("{a.a.a=", deep) + "1" + repeat("}", deep) + "\n", 1},
                        Case{"unclosed", "x = " + repeat("[{a=", deep), 1}}) {
    SCOPED_TRACE(c.name);
    EXPECT_EQ(message_of(c.text, "deep.toml"), "deep.toml:" + std::to_string(c.line) + kTooDeep);
  }
}

TEST(SceneFile, NestingUpToTheLimitReachesTheParser) {
  // At the limit the pre-scan lets the text through (the reader then finds
  // an unknown key); one level more is refused.
  auto dotted = [](int parts) { return "a" + repeat(".a", parts - 1); };
  EXPECT_NE(message_of(dotted(max_scene_nesting) + " = 1\n").find("unknown key"), std::string::npos);
  EXPECT_EQ(message_of(dotted(max_scene_nesting + 1) + " = 1\n"), "scene.toml:1" + kTooDeep);
  EXPECT_NE(message_of("[" + dotted(max_scene_nesting - 1) + "]\nb = 1\n").find("unknown key"), std::string::npos);
  EXPECT_EQ(message_of("[" + dotted(max_scene_nesting) + "]\nb = 1\n"), "scene.toml:2" + kTooDeep);
  const std::string arrays = repeat("[", max_scene_nesting - 1) + repeat("]", max_scene_nesting - 1);
  EXPECT_NE(message_of("x = " + arrays + "\n").find("unknown key"), std::string::npos);
  EXPECT_EQ(message_of("x = [" + arrays + "]\n"), "scene.toml:1" + kTooDeep);
  // Brackets and dots inside strings and comments are no nesting.
  const std::string many = repeat("[", 100) + repeat(".", 100) + repeat("{", 100) + "\\\"";
  const Scene s = parse_scene("title = \"" + many + "\"  # " + many + "\n# " + many + "\nfall_speed = 1.5\n" +
                                  "[dissipation]\ncoupling = [ { pairs = [\"1-2\", \"2-3\"], value = -1.0 } ]\n" +
                                  "[[body]]\nmass = 1\n[[body]]\nmass = 2\n[[body]]\nmass = \"inf\"\n",
                              "strings.toml");
  EXPECT_EQ(s.title.size(), 301u);
  EXPECT_EQ(s.entries.size(), 1u);
  EXPECT_EQ(message_of("title = \"\"\"\n" + many + "\n\"\"\"\nfall_speed = 1\n" + kTwoBodies), "");
  EXPECT_EQ(message_of("title = '''\n" + many + "\n'''\nfall_speed = 1\n" + kTwoBodies), "");
  EXPECT_EQ(message_of("title = '" + many + "'\nfall_speed = 1\n" + kTwoBodies), "");
}

/// Writes \p text into \p fd from another thread (as a shell pipe would),
/// counting what the reader took; closes \p fd at the end.
class Writer {
 public:
  Writer(int fd, std::string text)
      : thread_([this, fd, text = std::move(text)] {
          for (std::size_t at = 0; at < text.size();) {
            const ssize_t n = ::write(fd, text.data() + at, text.size() - at);
            if (n <= 0) break;  // the reader closed its end (EPIPE)
            at += static_cast<std::size_t>(n);
            written_ = at;
          }
          ::close(fd);
        }) {}
  ~Writer() { join(); }
  std::size_t join() {
    if (thread_.joinable()) thread_.join();
    return written_;
  }

 private:
  std::size_t written_ = 0;
  std::thread thread_;
};

/// Standard input replaced by the read end of a pipe for one test.
class PipedStdin {
 public:
  PipedStdin() {
    int fds[2];
    if (::pipe(fds) != 0) throw std::runtime_error("pipe failed");
    saved_ = ::dup(STDIN_FILENO);
    ::dup2(fds[0], STDIN_FILENO);
    ::close(fds[0]);
    write_end_ = fds[1];
  }
  ~PipedStdin() {
    ::dup2(saved_, STDIN_FILENO);
    ::close(saved_);
  }
  int write_end() const { return write_end_; }

 private:
  int saved_ = -1, write_end_ = -1;
};

/// SIGPIPE ignored for one test: a writer whose reader has gone gets EPIPE.
class IgnoreSigpipe {
 public:
  IgnoreSigpipe() : old_(std::signal(SIGPIPE, SIG_IGN)) {}
  ~IgnoreSigpipe() { std::signal(SIGPIPE, old_); }

 private:
  void (*old_)(int);
};

TEST(SceneFile, DashReadsStandardInput) {
  PipedStdin in;
  {
    Writer w(in.write_end(), "fall_speed = 2.5\n" + kTwoBodies);
    const Scene s = load_scene("-");
    EXPECT_EQ(s.origin, "<stdin>");
    EXPECT_EQ(s.fall_speed->fraction(), "25/10");
  }
  PipedStdin bad;
  Writer w(bad.write_end(), "fall_speed = -1\n" + kTwoBodies);
  EXPECT_EQ(load_message("-"), "<stdin>:1:14: fall_speed: must be >= 0 (a speed; bodies fall at -fall_speed)");
}

TEST(SceneFile, StreamsAreCutAtTheSizeLimitWhileReading) {
  // A stream that does not end (here twice the limit) is refused once it has
  // given one byte more than the limit: the writer is left with the rest.
  IgnoreSigpipe ignore;
  PipedStdin in;
  const std::string text = "fall_speed = 1\n" + kTwoBodies + "#" + std::string(2 * max_scene_file_bytes, '#') + "\n";
  Writer w(in.write_end(), text);
  EXPECT_EQ(load_message("-"), "<stdin>: more than " + std::to_string(max_scene_file_bytes) + " bytes; a scene file has at most " +
                                   std::to_string(max_scene_file_bytes));
  ::close(STDIN_FILENO);  // the reader is gone: the writer stops (EPIPE)
  const std::size_t written = w.join();
  const auto pipe_buffer = static_cast<std::size_t>(1) << 20;  // Linux's largest default pipe buffer
  EXPECT_LE(written, max_scene_file_bytes + 1 + pipe_buffer);
  EXPECT_LT(written, text.size());
}

TEST(SceneFile, FifoIsReadAsAStream) {
  TemporaryDirectory dir;
  const std::string fifo = dir / "scene.fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
  std::thread writer([&] {
    const int fd = ::open(fifo.c_str(), O_WRONLY);  // waits for the reader
    const std::string text = "drop_height = 0.5\n" + kTwoBodies;
    if (fd >= 0 && ::write(fd, text.data(), text.size()) < 0) std::perror("write");
    if (fd >= 0) ::close(fd);
  });
  std::optional<Scene> s;
  try {
    s = load_scene(fifo);
  } catch (const InputError& e) {
    ADD_FAILURE() << e.what();
    ::close(::open(fifo.c_str(), O_RDONLY | O_NONBLOCK));  // lets the writer's open return
  }
  writer.join();
  ASSERT_TRUE(s);
  EXPECT_EQ(s->origin, fifo);
  EXPECT_EQ(s->drop_height->fraction(), "5/10");
}

TEST(SceneFile, DirectorySocketAndDeviceGetAPlainReason) {
  TemporaryDirectory dir;
  const std::string folder = dir / "folder.toml";
  std::filesystem::create_directory(folder);
  EXPECT_EQ(load_message(folder), folder + ": is a directory, not a scene file");
  std::filesystem::create_directory_symlink(folder, dir / "link.toml");
  EXPECT_EQ(load_message(dir / "link.toml"), dir / "link.toml" + ": is a directory, not a scene file");

  const std::string socket_path = dir / "s.toml";
  const int sock = ::socket(AF_UNIX, SOCK_STREAM, 0);
  ASSERT_GE(sock, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  if (socket_path.size() < sizeof address.sun_path) {
    std::strcpy(address.sun_path, socket_path.c_str());
    ASSERT_EQ(::bind(sock, reinterpret_cast<sockaddr*>(&address), sizeof address), 0) << std::strerror(errno);
    EXPECT_EQ(load_message(socket_path), socket_path + ": is a socket, not a scene file");
  }
  ::close(sock);

  // A character device of our own (the numbers of /dev/null): refused
  // without being opened.  Making one needs privileges.
  const std::string device = dir / "device.toml";
  if (::mknod(device.c_str(), S_IFCHR | 0600, makedev(1, 3)) != 0)
    GTEST_SKIP() << "cannot make a device node here (" << std::strerror(errno) << "); the device case is not tested";
  EXPECT_EQ(load_message(device), device + ": is a device, not a scene file");
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

// scene_from_value(): a scene built from a front's structured value (no text)
// is read by the same reader as a file: the same scene, the same checks,
// messages naming the field without a line and column.

SceneValue str(const std::string& t) { return {SceneValue::Kind::String, t, false, {}, {}}; }
SceneValue table(std::vector<std::pair<std::string, SceneValue>> members) { return {SceneValue::Kind::Table, "", false, std::move(members), {}}; }
SceneValue array(std::vector<SceneValue> items) { return {SceneValue::Kind::Array, "", false, {}, std::move(items)}; }

SceneValue paper_value(const std::string& first_mass) {
  return table({{"title", str("Paper 4.4 read with alpha_2 = -100 (reproduces eq. 16)")},
                {"fall_speed", str("3.13209")},
                {"body", array({table({{"mass", str(first_mass)}}), table({{"mass", str("10")}}), table({{"mass", str("15")}}),
                                table({{"mass", str("5e6")}, {"velocity", str("0")}})})},
                {"dissipation", table({{"K", table({{"1-2", str("7")}, {"1-3", str("7")}, {"1-4", str("1500")}, {"2-3", str("10")},
                                                    {"2-4", str("13")}, {"3-4", str("10")}})},
                                       {"alpha", table({{"2", str("-100")}})}})}});
}

std::string value_message(const SceneValue& v) {
  try {
    scene_from_value(v, "<dict>");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(SceneFromValue, IsTheSceneOfTheSameFile) {
  const Scene a = scene_from_value(paper_value("0.001"), "<dict>");
  const Scene b = load_scene(kScenes + "paper-4.4-alpha2.toml");
  EXPECT_EQ(a.origin, "<dict>");
  expect_same_scene(a, b);
  EXPECT_EQ(write_scene(a), write_scene(b));
  EXPECT_EQ(entry(a, "1-2", "1-4").value.fraction(), "-100/1");
  EXPECT_EQ(a.bodies[0].mass.fraction(), "1/1000");
}

TEST(SceneFromValue, MessagesNameTheField) {
  EXPECT_EQ(value_message(paper_value("-1")), "<dict>: body[1].mass: must be > 0 (got -1)");
  SceneValue v = paper_value("1");
  v.members.push_back({"colour", str("red")});
  EXPECT_EQ(value_message(v), "<dict>: colour: unknown key (expected one of: body, dissipation, drop, drop_height, fall_speed, flight, g, title)");
  v = paper_value("1");
  v.members[2].second.items[1].members[0].second = {SceneValue::Kind::Boolean, "", true, {}, {}};
  EXPECT_EQ(value_message(v), "<dict>: body[2].mass: must be a number or a fraction string like \"1/3\" (got a boolean)");
  v = paper_value("1");
  v.members[3].second.members[0].second.members.push_back({"1-9", str("1")});
  EXPECT_EQ(value_message(v), "<dict>: dissipation.K.1-9: pair 1-9 is outside bodies 1..4");
  v = paper_value("1");
  v.members.push_back({"title", str("again")});
  EXPECT_EQ(value_message(v), "<dict>: title: given twice");
  SceneValue deep = str("1");
  for (int k = 0; k < 20; ++k) deep = array({deep});
  v = paper_value("1");
  v.members.push_back({"g", deep});
  std::string field = "g";
  for (int k = 0; k < 16; ++k) field += "[1]";
  EXPECT_EQ(value_message(v), "<dict>: " + field + ": tables and arrays nest deeper than 16 levels (a scene needs a few)");
  EXPECT_EQ(value_message(str("x")), "<dict>: a scene is a table of keys (title, body, ...)");
}

}  // namespace
}  // namespace superball
