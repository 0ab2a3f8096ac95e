// A map's grid as CSV and JSON written in pieces on several threads
// (present::write_map_csv(), write_map_json()) is byte for byte the text made
// whole on one thread (map_csv(), map_json().dump(1)): on grids of several
// blocks of points, with points outside the PSD cone, several cases on both
// sides of the superball edge, and members added after the map's own.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <string_view>

#include "superball/cases/scene_file.hpp"
#include "superball/numeric/map.hpp"
#include "superball/present/map.hpp"

namespace {

using namespace superball;

/// The pieces given to a sink, joined, and how many there were.
struct Pieces {
  std::string text;
  int count = 0;
  present::TextSink sink() {
    return [this](std::string_view piece) { text += piece, ++count; };
  }
};

numeric::Map paper_map(int nx, int ny) {
  const Scene s = load_scene(std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-4.4-alpha2.toml");
  const numeric::Axis x{Parameter::parse("K.3-4", s), 0, 20, nx}, y{Parameter::parse("alpha.2", s), -110, 0, ny};
  numeric::MapSettings settings;
  settings.threads = 2;
  return numeric::map(s, x, y, settings);
}

TEST(MapOutput, CsvWrittenOnThreadsIsTheCsvMadeWhole) {
  const numeric::Map m = paper_map(101, 90);  // 9090 points: three blocks of rows
  const std::string whole = present::map_csv(m);
  ASSERT_NE(whole.find(",0,,,,,\n"), std::string::npos);  // points outside the cone
  for (int threads : {1, 2, 3}) {
    Pieces pieces;
    present::write_map_csv(m, threads, pieces.sink());
    EXPECT_TRUE(pieces.text == whole) << threads << " threads";
    EXPECT_EQ(pieces.count, 4) << "the header and three blocks";
    EXPECT_TRUE(present::map_csv(m, threads) == whole) << threads << " threads";
    // A block of rows that starts inside a row, as the streamed CSV's blocks do.
    const std::vector<numeric::MapPoint> some(m.points.begin() + 150, m.points.begin() + 5000);
    const std::string rows = present::map_csv_rows(m.x, m.y, 150, some, threads);
    const std::size_t from = whole.find('\n') + 1;
    std::size_t start = from, end = from;
    for (int k = 0; k < 150; ++k) start = whole.find('\n', start) + 1;
    end = start;
    for (int k = 0; k < 4850; ++k) end = whole.find('\n', end) + 1;
    EXPECT_TRUE(rows == whole.substr(start, end - start)) << threads << " threads";
  }
}

TEST(MapOutput, JsonWrittenOnThreadsIsTheDumpOfMapJson) {
  const Scene s = load_scene(std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-4.4-alpha2.toml");
  for (const auto& [nx, ny] : {std::pair<int, int>{101, 90}, {3, 2}}) {
    const numeric::Map m = paper_map(nx, ny);
    nlohmann::ordered_json extra = nlohmann::ordered_json::object();
    for (bool with_extra : {false, true}) {
      nlohmann::ordered_json j = present::map_json(m, s, "double");
      if (with_extra) {
        extra["overlay"] = {{"agrees", true}, {"zeros", nlohmann::ordered_json::array({1.5, "a\nb"})}};
        j["overlay"] = extra["overlay"];
      }
      const std::string whole = j.dump(1) + "\n";
      for (int threads : {1, 2, 3}) {
        Pieces pieces;
        present::write_map_json(m, s, "double", extra, threads, pieces.sink());
        EXPECT_TRUE(pieces.text == whole) << nx << " x " << ny << ", " << threads << " threads, extra " << with_extra;
      }
      EXPECT_EQ(nlohmann::ordered_json::parse(whole)["points"].size(), static_cast<std::size_t>(nx * ny));
    }
  }
}

TEST(MapOutput, ManyWindowsAreWrittenInOrderOneCallAtATimeAndASinksErrorComesOut) {
  // 400 x 400 points: 40 blocks, more than two windows of blocks on 1 and 2
  // threads (the sink writes a window while the next is formatted).
  const numeric::Map m = paper_map(400, 400);
  const std::string whole = present::map_csv(m);
  for (int threads : {1, 2, 3}) {
    std::string text;
    std::atomic<int> inside{0};
    int overlaps = 0, calls = 0;
    present::write_map_csv(m, threads, [&](std::string_view piece) {
      if (inside.fetch_add(1) != 0) ++overlaps;
      text += piece;
      ++calls;
      inside.fetch_sub(1);
    });
    EXPECT_TRUE(text == whole) << threads << " threads";
    EXPECT_EQ(calls, 41) << "the header and 40 blocks";
    EXPECT_EQ(overlaps, 0) << threads << " threads";
    // A sink that fails at its 20th piece (a full disk): its exception, and no piece after it.
    int given = 0;
    EXPECT_THROW(present::write_map_csv(m, threads,
                                        [&](std::string_view) {
                                          if (++given == 20) throw std::runtime_error("disk full");
                                        }),
                 std::runtime_error)
        << threads << " threads";
    EXPECT_EQ(given, 20) << threads << " threads";
  }
}

}  // namespace
