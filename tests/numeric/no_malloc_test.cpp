// No heap allocation in a double solve of 4 bodies on a warmed-up solver
// (issue 2: "for n = 4 in double, no heap allocation in the solve").
//
// Two detectors, both armed only around the second compute():
//  - Eigen's own: this executable compiles numeric/src/collision/collision.cpp again
//    with EIGEN_RUNTIME_NO_MALLOC (eigen_no_malloc.hpp), and the test calls
//    Eigen::internal::set_is_malloc_allowed(false);
//  - a count of every malloc/calloc/realloc of the process (glibc: the
//    functions below replace the library's and forward to __libc_*), which
//    also sees std::vector and std::string, which Eigen does not.
// The capacities and data pointers of the Solution's vectors must not change.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

#include "superball/cases/scene_file.hpp"
#include "superball/numeric/collision.hpp"
#include "superball/numeric/problem.hpp"

namespace superball::testing {

int eigen_failures = 0;
std::string eigen_first_failure;

void eigen_assertion_failed(const char* what, const char* file, int line) {
  ++eigen_failures;
  if (eigen_first_failure.empty()) eigen_first_failure = std::string(what) + " (" + file + ":" + std::to_string(line) + ")";
}

}  // namespace superball::testing

// Under AddressSanitizer malloc belongs to the sanitizer: the counter is left
// out there (the Eigen check still runs).  GCC says AddressSanitizer with
// __SANITIZE_ADDRESS__, clang with __has_feature(address_sanitizer).
#if defined(__SANITIZE_ADDRESS__)
#define SUPERBALL_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SUPERBALL_TEST_ASAN 1
#endif
#endif
#if defined(__GLIBC__) && !defined(SUPERBALL_TEST_ASAN)
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void __libc_free(void*);
}
namespace {
bool g_counting = false;
long g_allocations = 0;
}  // namespace
extern "C" {
void* malloc(std::size_t size) {
  if (g_counting) ++g_allocations;
  return __libc_malloc(size);
}
void* calloc(std::size_t n, std::size_t size) {
  if (g_counting) ++g_allocations;
  return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t size) {
  if (g_counting) ++g_allocations;
  return __libc_realloc(p, size);
}
void free(void* p) { __libc_free(p); }
}
constexpr bool kCountsMalloc = true;
#else
namespace {
bool g_counting = false;
long g_allocations = 0;
}  // namespace
constexpr bool kCountsMalloc = false;
#endif

namespace superball::testing {
namespace {

using numeric::CollisionSolver;
using numeric::Problem;
using numeric::Solution;

/// Heap allocations seen while running \p f, by both detectors.
struct Allocations {
  long malloc_calls = 0;
  int eigen = 0;
  std::string eigen_first;
};

template <class F>
Allocations watch(F&& f) {
  const int before = eigen_failures;
  eigen_first_failure.clear();
  Eigen::internal::set_is_malloc_allowed(false);
  g_allocations = 0;
  g_counting = true;
  f();
  g_counting = false;
  Eigen::internal::set_is_malloc_allowed(true);
  return {g_allocations, eigen_failures - before, eigen_first_failure};
}

Problem<double> problem(const std::string& toml) {
  return Problem<double>::from(numeric::ExactScene::from(parse_scene(toml, "no-malloc")));
}

const std::string kScenes = std::string(SUPERBALL_CASES_DIR) + "/scenes/";

std::vector<Problem<double>> four_body_problems() {
  std::vector<Problem<double>> out;
  for (const char* f : {"paper-4.4-alpha2.toml", "paper-4.4-as-printed.toml", "paper-fig5-alpha5.toml"})
    out.push_back(Problem<double>::from(numeric::ExactScene::from(load_scene(kScenes + f))));
  // Closed contacts (case 2.2 at K34 = 2, and a fixed obstacle): pivots happen.
  out.push_back(problem(
      "fall_speed = 3.13209\n[[body]]\nmass = 0.001\n[[body]]\nmass = 10\n[[body]]\nmass = 15\n[[body]]\nmass = 5e6\n"
      "velocity = 0\n[dissipation]\nK = { \"1-2\" = 7, \"1-3\" = 7, \"1-4\" = 1500, \"2-3\" = 10, \"2-4\" = 13, \"3-4\" = 2 }\n"
      "alpha = { \"2\" = -100 }\n"));
  out.push_back(problem(
      "fall_speed = 1\n[[body]]\nmass = \"1/1000000\"\n[[body]]\nmass = 10\n[[body]]\nmass = 10\n[[body]]\nmass = \"inf\"\n"
      "[dissipation]\nK = { \"1-2\" = \"9901/10000\", \"1-3\" = \"1/10000\", \"1-4\" = \"101/100\", \"2-3\" = 1, "
      "\"2-4\" = 1, \"3-4\" = 1 }\nalpha = { \"2\" = -1 }\n"));
  return out;
}

TEST(NoHeapAllocation, TheDetectorsWork) {
  // Without these the test below could not fail.
  const Allocations eigen = watch([] {
    Eigen::VectorXd v(100);
    v.setZero();
  });
  EXPECT_GT(eigen.eigen, 0) << "Eigen's EIGEN_RUNTIME_NO_MALLOC check is not active";
  if (kCountsMalloc) {
    const Allocations vec = watch([] {
      std::vector<int> v(100);
      v[0] = 1;
    });
    EXPECT_GT(vec.malloc_calls, 0) << "the malloc counter is not active";
  }
  const Allocations none = watch([] {
    volatile int x = 0;
    x = x + 1;
  });
  EXPECT_EQ(none.malloc_calls, 0);
  EXPECT_EQ(none.eigen, 0);
}

TEST(NoHeapAllocation, DoubleSolveOfFourBodiesOnAWarmSolver) {
  const auto problems = four_body_problems();
  for (std::size_t k = 0; k < problems.size(); ++k) {
    SCOPED_TRACE("problem " + std::to_string(k));
    const Problem<double>& p = problems[k];
    CollisionSolver<double> solver(numeric::Settings<double>::defaults());
    Solution<double> out;
    solver.compute(p, out);  // warm up: sizes the workspace and the output
    const Solution<double> first = out;
    const auto cap_v = out.velocities_after.capacity(), cap_r = out.reactions.capacity(), cap_g = out.gaps.capacity();
    const double *data_v = out.velocities_after.data(), *data_r = out.reactions.data(), *data_g = out.gaps.data();
    const Allocations a = watch([&] { solver.compute(p, out); });
    EXPECT_EQ(a.eigen, 0) << "Eigen: " << a.eigen_first;
    EXPECT_EQ(a.malloc_calls, 0) << "heap allocations in the second compute()";
    EXPECT_EQ(out.velocities_after.capacity(), cap_v);
    EXPECT_EQ(out.reactions.capacity(), cap_r);
    EXPECT_EQ(out.gaps.capacity(), cap_g);
    EXPECT_EQ(out.velocities_after.data(), data_v);
    EXPECT_EQ(out.reactions.data(), data_r);
    EXPECT_EQ(out.gaps.data(), data_g);
    // And the same answer.
    EXPECT_EQ(out.status, first.status);
    EXPECT_EQ(out.closed, first.closed);
    EXPECT_EQ(out.velocities_after, first.velocities_after);
    EXPECT_EQ(out.reactions, first.reactions);
  }
}

TEST(NoHeapAllocation, OneWarmSolverForManyFourBodyProblems) {
  // A sweep reuses one solver and one output across problems of one size
  // (4 bodies, all finite: a fixed obstacle has one free body less, hence
  // another workspace size).
  auto problems = four_body_problems();
  problems.erase(std::remove_if(problems.begin(), problems.end(), [](const auto& p) { return p.fixed_bottom; }), problems.end());
  ASSERT_GE(problems.size(), 4u);
  CollisionSolver<double> solver(numeric::Settings<double>::defaults());
  Solution<double> out;
  for (const auto& p : problems) solver.compute(p, out);  // warm up on all of them
  for (std::size_t k = 0; k < problems.size(); ++k) {
    SCOPED_TRACE("problem " + std::to_string(k));
    const Allocations a = watch([&] { solver.compute(problems[k], out); });
    EXPECT_EQ(a.eigen, 0) << "Eigen: " << a.eigen_first;
    EXPECT_EQ(a.malloc_calls, 0);
    const auto fresh = numeric::solve(problems[k]);
    EXPECT_EQ(out.velocities_after, fresh.velocities_after);
    EXPECT_EQ(out.closed, fresh.closed);
  }
}

TEST(NoHeapAllocation, NoEigenAssertionFailedAnywhere) {
  // The recording eigen_assert also catches index errors in the solver's
  // Eigen code (compiled out by NDEBUG otherwise): none in solves of every size from 2 to 12, with and without a fixed obstacle.
  const int before = eigen_failures;
  eigen_first_failure.clear();
  for (int n = 2; n <= 12; ++n)
    for (bool fixed : {false, true}) {
      std::string toml = "fall_speed = 2\n";
      for (int i = 1; i <= n; ++i)
        toml += i == n && fixed ? "[[body]]\nmass = \"inf\"\n" : "[[body]]\nmass = " + std::to_string(i) + (i == n ? "\nvelocity = 0\n" : "\n");
      toml += "[dissipation]\nK = { \"1-" + std::to_string(n) + "\" = 3 }\n";
      const auto s = numeric::solve(problem(toml));
      EXPECT_EQ(s.status, numeric::Status::Success) << toml;
    }
  EXPECT_EQ(eigen_failures, before) << "an eigen_assert failed: " << eigen_first_failure;
}

}  // namespace
}  // namespace superball::testing
