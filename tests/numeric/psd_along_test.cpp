// psd_along(): where M stays positive semi-definite along one parameter,
// against positive_semidefinite() of each value's scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

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

}  // namespace
}  // namespace superball::numeric
