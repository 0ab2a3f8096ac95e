// psd_along(): where M stays positive semi-definite along one parameter,
// against positive_semidefinite() of each value's scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "superball/cases/error.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/numeric/problem.hpp"
#include "superball/numeric/psd_along.hpp"
#include "superball/numeric/sweep.hpp"

namespace superball::numeric {
namespace {

const std::string kPaper = std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-4.4-alpha2.toml";

/// The verdict of each value's scene on its own.
std::vector<bool> one_by_one(const Scene& scene, const Parameter& p, const std::vector<cln::cl_RA>& values) {
  std::vector<bool> out;
  for (const auto& v : values) {
    Scene s = scene;
    p.assign(s, Number::parse(to_string(v)));
    out.push_back(positive_semidefinite(ExactScene::from(s, ExactScene::MCheck::Caller)));
  }
  return out;
}

TEST(PsdAlong, IsEachValuesVerdict) {
  const Scene scene = load_scene(kPaper);
  const Parameter alpha = Parameter::parse("alpha.2", scene);
  // alpha.2 from -300 to 300: M is PSD for |alpha2| up to about 102.47 (the map's edge), so both ends are out.
  for (int steps : {2, 3, 7, 601, 5001}) {
    const auto values = linspace(cln::cl_RA(-300), cln::cl_RA(300), steps);
    EXPECT_EQ(psd_along(scene, alpha, values), one_by_one(scene, alpha, values)) << steps;
  }
  // in decreasing order, and shuffled: the same verdict per value
  std::vector<cln::cl_RA> values = linspace(cln::cl_RA(200), cln::cl_RA(-200), 41);
  std::swap(values[3], values[30]);
  EXPECT_EQ(psd_along(scene, alpha, values), one_by_one(scene, alpha, values));
  // a PSD run narrower than the sampling stride, between two samples
  values = linspace(cln::cl_RA(-100000), cln::cl_RA(100000), 20001);
  const auto marked = psd_along(scene, alpha, values);
  EXPECT_EQ(marked, one_by_one(scene, alpha, values));
  EXPECT_EQ(std::count(marked.begin(), marked.end(), true), 21);
}

TEST(PsdAlong, NotAnEntryOfMKeepsTheScenesVerdict) {
  const Scene scene = load_scene(kPaper);
  const auto values = linspace(cln::cl_RA(1), cln::cl_RA(50), 9);
  const auto marked = psd_along(scene, Parameter::parse("mass.2", scene), values);
  EXPECT_EQ(marked, std::vector<bool>(9, true));
}

// Issue 26: a sweep through M's PSD bound marks exactly the values where M is
// not PSD (each value's verdict on its own) and solves the others as a sweep
// of those alone, bit for bit, in chunks of sweep_chunk_values.
TEST(SweepMarkingPsd, MarksTheNonPsdValuesAndSolvesTheOthersAsSweep) {
  const Scene scene = load_scene(kPaper);
  const Parameter alpha = Parameter::parse("alpha.2", scene);
  for (int steps : {221, 140001}) {  // alpha2 from -110 to 0: M is PSD from about -102.47
    const auto values = linspace(cln::cl_RA(-110), cln::cl_RA(0), steps);
    std::vector<std::size_t> delivered;
    std::vector<SweepPoint> points;
    std::vector<std::pair<std::size_t, std::size_t>> told;
    const std::vector<bool> psd = sweep_marking_psd(
        scene, alpha, values, Precision::parse("double"), 2,
        [&](std::size_t k, const SweepPoint& p) {
          delivered.push_back(k);
          points.push_back(p);
        },
        [&](std::size_t done, std::size_t total) { told.emplace_back(done, total); });
    if (steps == 221) {
      EXPECT_EQ(psd, one_by_one(scene, alpha, values));
    }
    std::vector<cln::cl_RA> only;
    std::vector<std::size_t> expected;
    for (std::size_t k = 0; k < values.size(); ++k)
      if (psd[k]) expected.push_back(k), only.push_back(values[k]);
    ASSERT_FALSE(only.empty());
    ASSERT_LT(only.size(), values.size());
    EXPECT_FALSE(psd.front());
    EXPECT_TRUE(psd.back());
    EXPECT_EQ(delivered, expected);
    const std::vector<SweepPoint> alone = sweep(scene, alpha, only, Precision::parse("double"), 1);
    ASSERT_EQ(points.size(), alone.size());
    for (std::size_t j = 0; j < alone.size(); ++j) {
      EXPECT_EQ(points[j].value, alone[j].value);
      EXPECT_EQ(points[j].velocities_after, alone[j].velocities_after) << j;  // bit for bit (no NaN among them)
      EXPECT_EQ(points[j].closed, alone[j].closed);
      EXPECT_EQ(points[j].status, alone[j].status);
    }
    std::vector<std::pair<std::size_t, std::size_t>> chunks;
    for (std::size_t first = 0; first < only.size(); first += sweep_chunk_values) chunks.emplace_back(first, only.size());
    chunks.emplace_back(only.size(), only.size());
    EXPECT_EQ(told, chunks);
  }
}

// Through a runner (a checkpoint), each chunk crosses as write_sweep_points() text: the points read back are
// the points solved here, bit for bit; a damaged text is refused.
TEST(SweepMarkingPsd, ThroughARunnerTheTextReadsBackBitForBit) {
  const Scene scene = load_scene(kPaper);
  const Parameter alpha = Parameter::parse("alpha.2", scene);
  const auto values = linspace(cln::cl_RA(-110), cln::cl_RA(0), 80001);  // about 74,500 PSD values
  const Precision dbl = Precision::parse("double");
  auto collect = [&](const TaskRunner& runner) {
    std::vector<std::pair<std::size_t, SweepPoint>> got;
    sweep_marking_psd(scene, alpha, values, dbl, 2, [&](std::size_t k, const SweepPoint& p) { got.emplace_back(k, p); }, {}, runner);
    return got;
  };
  std::size_t tasks = 0;
  const TaskRunner local = [&](std::size_t count, const std::function<std::string(std::size_t)>& task) {
    tasks = count;
    std::vector<std::string> texts;
    for (std::size_t t = 0; t < count; ++t) texts.push_back(task(t));
    return texts;
  };
  const auto direct = collect({}), through = collect(local);
  EXPECT_EQ(tasks, 2u);  // the PSD values (more than one chunk) in chunks of sweep_chunk_values
  ASSERT_EQ(direct.size(), through.size());
  for (std::size_t j = 0; j < direct.size(); ++j) {
    EXPECT_EQ(direct[j].first, through[j].first);
    EXPECT_EQ(direct[j].second.value, through[j].second.value);
    EXPECT_EQ(direct[j].second.velocities_after, through[j].second.velocities_after) << j;
    EXPECT_EQ(direct[j].second.closed, through[j].second.closed);
    EXPECT_EQ(direct[j].second.status, through[j].second.status);
  }
  const TaskRunner cut = [&](std::size_t count, const std::function<std::string(std::size_t)>& task) {
    std::vector<std::string> texts = local(count, task);
    texts.back().pop_back();  // its last line cut
    return texts;
  };
  EXPECT_THROW(collect(cut), std::invalid_argument);
  EXPECT_THROW(read_sweep_points("1 2 3 4 none success\n", 3), std::invalid_argument);  // a row of the wrong fields
  EXPECT_THROW(read_sweep_points("1 2 x 4 none success\n", 4), std::invalid_argument);
  EXPECT_THROW(read_sweep_points("1 2 3 4 9-9 success\n", 4), std::invalid_argument);
  EXPECT_THROW(read_sweep_points("1 2 3 4 none fine\n", 4), std::invalid_argument);
  EXPECT_EQ(read_sweep_points("1 2 3 4 2-3 success\n", 4).size(), 1u);
}

TEST(SweepMarkingPsd, RefusesWhatItCannotSolveBeforeSolving) {
  const Scene scene = load_scene(kPaper);
  const Parameter alpha = Parameter::parse("alpha.2", scene);
  int delivered = 0;
  auto count = [&](std::size_t, const SweepPoint&) { ++delivered; };
  const Precision dbl = Precision::parse("double");
  try {
    sweep_marking_psd(scene, alpha, linspace(cln::cl_RA(-300), cln::cl_RA(-200), 5), dbl, 1, count);
    ADD_FAILURE() << "no PSD value accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), kPaper + ": M is not positive semi-definite at any value of the sweep (alpha.2 from -300 to -200): nothing to solve");
  }
  EXPECT_THROW(sweep_marking_psd(scene, alpha, {}, dbl, 1, count), std::invalid_argument);
  EXPECT_THROW(sweep_marking_psd(scene, alpha, {cln::cl_RA(-50)}, dbl, -1, count), std::invalid_argument);
  // another inadmissible value among the PSD ones: check_range()'s refusal (a mass <= 0)
  EXPECT_THROW(sweep_marking_psd(scene, Parameter::parse("mass.2", scene), linspace(cln::cl_RA(-1), cln::cl_RA(1), 3), dbl, 1, count), InputError);
  EXPECT_EQ(delivered, 0);
}

}  // namespace
}  // namespace superball::numeric
