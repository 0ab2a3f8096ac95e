// The catalogue of malformed or unphysical scenes (tests/data/bad): one test
// per file.  Each file starts with "# expect: TEXT"; reading it with
// load_scene() and checking it with ExactScene::from() must throw
// superball::InputError whose message is one line, starts with the file's
// path and contains TEXT.  Files too big to commit (a file over the size
// limit, a scene with too many bodies) are generated at test time.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "superball/cases/scene_file.hpp"
#include "superball/numeric/problem.hpp"

namespace superball {
namespace {

const std::string kBad = std::string(SUPERBALL_TEST_DATA_DIR) + "/bad/";

/// The catalogue as CMake saw it (generated from tests/data/bad/*.toml).
const std::vector<std::string> kCatalogue = {
#include "bad_scene_list.inc"
};

/// What happened when a scene file was read and checked.
struct Outcome {
  bool accepted = false;
  bool input_error = false;
  std::string message;
};

Outcome read_and_check(const std::string& path) {
  Outcome o;
  try {
    const Scene scene = load_scene(path);
    numeric::ExactScene::from(scene);
    o.accepted = true;
  } catch (const InputError& e) {
    o.input_error = true;
    o.message = e.what();
  } catch (const std::exception& e) {
    o.message = std::string("another exception: ") + e.what();
  }
  return o;
}

/// The expected substring, from the first line "# expect: TEXT".
std::string expectation(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string first;
  std::getline(in, first);
  const std::string tag = "# expect: ";
  return first.rfind(tag, 0) == 0 ? first.substr(tag.size()) : "";
}

void expect_one_clear_line(const Outcome& o, const std::string& path, const std::string& expected) {
  ASSERT_FALSE(o.accepted) << path << " was accepted";
  ASSERT_TRUE(o.input_error) << path << ": " << o.message;
  EXPECT_EQ(o.message.rfind(path, 0), 0u) << "the message does not start with the file: " << o.message;
  EXPECT_NE(o.message.find(expected), std::string::npos) << "expected '" << expected << "' in: " << o.message;
  EXPECT_EQ(o.message.find('\n'), std::string::npos) << "more than one line: " << o.message;
  EXPECT_EQ(o.message.find('\r'), std::string::npos) << o.message;
  EXPECT_GT(o.message.size(), path.size() + 4) << "no reason given: " << o.message;
}

class BadScene : public ::testing::TestWithParam<std::string> {};

TEST_P(BadScene, IsRejectedWithOneClearLine) {
  const std::string path = kBad + GetParam();
  const std::string expected = expectation(path);
  ASSERT_FALSE(expected.empty()) << path << " does not start with '# expect: '";
  expect_one_clear_line(read_and_check(path), path, expected);
}

std::string test_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param.substr(0, info.param.rfind('.'));
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Catalogue, BadScene, ::testing::ValuesIn(kCatalogue), test_name);

TEST(BadSceneCatalogue, IsCompleteAndLargeEnough) {
  // The list compiled in is the folder's (CMake globs it at configure time).
  std::vector<std::string> files;
  for (const auto& f : std::filesystem::directory_iterator(kBad))
    if (f.path().extension() == ".toml") files.push_back(f.path().filename().string());
  std::sort(files.begin(), files.end());
  std::vector<std::string> compiled = kCatalogue;
  std::sort(compiled.begin(), compiled.end());
  EXPECT_EQ(files, compiled) << "re-run cmake: the catalogue changed";
  EXPECT_GE(files.size(), 30u);
}

/// A scene file written for one test and removed after it.
class TemporaryFile {
 public:
  explicit TemporaryFile(const std::string& name)
      : path_(::testing::TempDir() + "superball-" + std::to_string(::getpid()) + "-" + name) {}
  ~TemporaryFile() { std::remove(path_.c_str()); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

TEST(BadSceneGenerated, FileOverTheSizeLimit) {
  // A valid scene padded with comments to one byte over the limit.
  TemporaryFile f("too-big.toml");
  {
    std::ofstream out(f.path(), std::ios::binary);
    std::string text = "fall_speed = 1\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n";
    const std::string line = "# padding padding padding padding padding padding padding padding\n";
    while (text.size() + line.size() <= max_scene_file_bytes) text += line;
    text += std::string(max_scene_file_bytes + 1 - text.size() - 1, '#') + "\n";
    ASSERT_EQ(text.size(), max_scene_file_bytes + 1);
    out << text;
  }
  expect_one_clear_line(read_and_check(f.path()), f.path(), "a scene file has at most " + std::to_string(max_scene_file_bytes));
}

TEST(BadSceneGenerated, FileAtTheSizeLimitIsRead) {
  TemporaryFile f("at-limit.toml");
  {
    std::ofstream out(f.path(), std::ios::binary);
    std::string text = "fall_speed = 1\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n#";
    text += std::string(max_scene_file_bytes - text.size() - 1, '#') + "\n";
    ASSERT_EQ(text.size(), max_scene_file_bytes);
    out << text;
  }
  const Outcome o = read_and_check(f.path());
  EXPECT_TRUE(o.accepted) << o.message;
}

TEST(BadSceneGenerated, TooManyBodies) {
  // max_scene_bodies + 1 bodies, as one inline array (about 1.2 MB).
  TemporaryFile f("too-many-bodies.toml");
  {
    std::ofstream out(f.path(), std::ios::binary);
    out << "fall_speed = 1\nbody = [";
    for (int k = 0; k <= max_scene_bodies; ++k) out << (k ? ",{mass=1}" : "{mass=1}");
    out << "]\n";
  }
  expect_one_clear_line(read_and_check(f.path()), f.path(), "at most " + std::to_string(max_scene_bodies) + " bodies");
}

TEST(BadSceneGenerated, MissingFileAndDirectory) {
  const std::string missing = kBad + "there-is-no-such-scene.toml";
  expect_one_clear_line(read_and_check(missing), missing, "cannot open");
  const std::string dir = kBad;
  const Outcome o = read_and_check(dir);
  EXPECT_FALSE(o.accepted);
  EXPECT_TRUE(o.input_error) << o.message;
  EXPECT_EQ(o.message.rfind(dir, 0), 0u) << o.message;
  EXPECT_EQ(o.message.find('\n'), std::string::npos) << o.message;
}

}  // namespace
}  // namespace superball
