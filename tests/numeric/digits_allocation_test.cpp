// A digits:N solve allocates nothing once its solver has sized its workspace
// (N <= 113 digits: MpFloat keeps its significand in the object): counted by
// replacing the global operator new of this test binary.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <string>

#include "superball/cases/scene_file.hpp"
#include "superball/numeric/collision.hpp"

namespace {
std::atomic<long> g_allocations{0};  ///< calls of operator new since the program started
}  // namespace

void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace superball::testing {
namespace {

using numeric::MpFloat;

/// Allocations made by \p solves solves of \p scene in digits:\p digits after a first one.
long allocations_per_solves(const std::string& scene, int digits, int solves) {
  const auto exact = numeric::ExactScene::from(load_scene(std::string(SUPERBALL_CASES_DIR) + "/scenes/" + scene));
  const auto problem = numeric::Problem<MpFloat>::from(exact, digits);
  numeric::CollisionSolver<MpFloat> solver(numeric::Settings<MpFloat>::defaults(digits));
  numeric::Solution<MpFloat> out;
  solver.compute(problem, out);  // sizes the workspace and the answer
  EXPECT_EQ(out.status, numeric::Status::Success) << scene << " digits:" << digits;
  const long before = g_allocations.load();
  for (int k = 0; k < solves; ++k) solver.compute(problem, out);
  return g_allocations.load() - before;
}

/// Whether this program is built with AddressSanitizer, whose own operator new
/// takes the place of the one above (nothing would be counted).
constexpr bool address_sanitizer() {
#if defined(__SANITIZE_ADDRESS__)
  return true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  return true;
#else
  return false;
#endif
#else
  return false;
#endif
}

TEST(DigitsAllocation, ASolveAllocatesNothingUpTo113Digits) {
  if (address_sanitizer()) GTEST_SKIP() << "AddressSanitizer's operator new replaces the counting one";
  for (const char* scene : {"paper-4.4-alpha2.toml", "hard-eps-1e-8.toml", "hard-mass-ratio-1e12.toml"})
    for (int digits : {20, 50, 100, 113}) EXPECT_EQ(allocations_per_solves(scene, digits, 20), 0) << scene << " digits:" << digits;
  // Beyond 113 digits the significands are on the heap: the count sees them.
  EXPECT_GT(allocations_per_solves("paper-4.4-alpha2.toml", 150, 20), 0);
}

}  // namespace
}  // namespace superball::testing
