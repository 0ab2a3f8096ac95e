// Sweeps and maps of drop scenes (numeric/sweep.hpp, numeric/map.hpp): the
// label of a drop is canonical (equal sequences of collisions, equal labels;
// runs written once), each value is drop() of the scene with the value set,
// bit for bit and whatever the threads, and the functions about one
// collision's exact solution refuse a drop scene.
#include <gtest/gtest.h>

#include <stdexcept>

#include "superball/cases/error.hpp"
#include "superball/cases/parameter.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/numeric/map.hpp"
#include "superball/numeric/sweep.hpp"

namespace superball::numeric {
namespace {

const std::string kTwo = std::string(SUPERBALL_CASES_DIR) + "/scenes/drop-two-balls.toml";

DropEvent event(std::vector<std::string> contacts, std::string case_name) {
  DropEvent e;
  e.contacts = std::move(contacts);
  e.case_name = std::move(case_name);
  return e;
}

TEST(DropLabel, RunsAreWrittenOnceAndEqualSequencesGiveEqualLabels) {
  DropResult r;
  EXPECT_EQ(drop_label(r), "none");
  r.events = {event({"2-3"}, "{}"), event({"1-2"}, "{}"), event({"2-3"}, "{}"), event({"2-3"}, "{}"), event({"2-3"}, "{}"),
              event({"1-2", "2-3"}, "{2-3}")};
  EXPECT_EQ(drop_label(r), "2-3:{} 1-2:{} 2-3:{}*3 1-2,2-3:{2-3}");
  // The same contacts with another case, or the same case at other contacts, is another label.
  DropResult other = r;
  other.events[1].case_name = "{1-2}";
  EXPECT_NE(drop_label(other), drop_label(r));
  other = r;
  other.events[5].contacts = {"1-2"};
  EXPECT_NE(drop_label(other), drop_label(r));
  // Times, velocities and energies are not part of it.
  other = r;
  other.events[0].time = 3;
  other.events[0].velocities_after = {1, 2, 3};
  EXPECT_EQ(drop_label(other), drop_label(r));
}

TEST(DropSweep, EachValueIsTheDropOfItsSceneBitForBitOnAnyThreads) {
  const Scene s = load_scene(kTwo);
  const Parameter gap = Parameter::parse("gap.1", s);
  const auto values = linspace(0, cln::cl_RA(1) / 100, 6);
  const auto one = drop_sweep(s, gap, values, Precision::parse("double"), 1);
  const auto two = drop_sweep(s, gap, values, Precision::parse("double"), 2);
  ASSERT_EQ(one.size(), values.size());
  for (std::size_t k = 0; k < values.size(); ++k) {
    const DropResult d = drop(with_value(s, gap, values[k]), Precision::parse("double"));
    EXPECT_EQ(one[k].ratio, d.top_apex_ratio) << k;
    EXPECT_EQ(one[k].label, drop_label(d)) << k;
    EXPECT_EQ(one[k].events, static_cast<int>(d.events.size()));
    EXPECT_EQ(one[k].end, d.end);
    EXPECT_EQ(two[k].ratio, one[k].ratio);
    EXPECT_EQ(two[k].label, one[k].label);
  }
  // Touching (gap 0), 1-2 stays closed; with a gap the floor, the balls, the floor.
  EXPECT_EQ(one[0].label, "2-3:{1-2}");
  EXPECT_EQ(one[1].label, "2-3:{} 1-2:{} 2-3:{}");
  EXPECT_GT(one[1].ratio, 8.9);
}

TEST(DropMap, EachPointIsItsDropAndTheMapRefusesWhatItCannotDo) {
  const Scene s = load_scene(kTwo);
  const Axis x{Parameter::parse("gap.1", s), 0, cln::cl_RA(1) / 100, 3};
  const Axis y{Parameter::parse("mass.1", s), cln::cl_RA(1) / 1000, cln::cl_RA(1) / 2, 3};
  MapSettings settings;
  settings.threads = 2;
  const DropMap m = drop_map(s, x, y, settings);
  ASSERT_EQ(m.points.size(), 9u);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const DropResult d = drop(with_value(with_value(s, x.parameter, x.values()[i]), y.parameter, y.values()[j]), settings.precision);
      EXPECT_EQ(m.at(i, j).ratio, d.top_apex_ratio);
      EXPECT_EQ(m.at(i, j).label, drop_label(d));
    }
  MapSettings runner = settings;
  runner.runner = [](std::size_t, const std::function<std::string(std::size_t)>&) { return std::vector<std::string>{}; };
  EXPECT_THROW(drop_map(s, x, y, runner), std::invalid_argument);
  EXPECT_THROW(drop_map(s, x, x, settings), std::invalid_argument);
  const Axis negative{Parameter::parse("gap.1", s), -1, 0, 3};
  EXPECT_THROW(drop_map(s, negative, y, settings), InputError);
  // One collision's exact solution: not of a drop scene.
  EXPECT_THROW(map(s, x, y, settings), std::invalid_argument);
  EXPECT_THROW(sweep(s, x.parameter, x.values(), Precision{}), std::invalid_argument);
  EXPECT_THROW(switch_points(s, x.parameter, x.values()), std::invalid_argument);
  // A scene without [drop] has no gap key, and drop_sweep() needs a drop scene.
  const Scene plain = load_scene(std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-4.4-alpha2.toml");
  EXPECT_THROW(Parameter::parse("gap.1", plain), std::invalid_argument);
  EXPECT_THROW(drop_sweep(plain, Parameter::parse("K.3-4", plain), {1, 2}, Precision{}), std::invalid_argument);
}

}  // namespace
}  // namespace superball::numeric
