// Sweeps on several threads (parallel.hpp): parallel_map hands results back
// in task order, builds each thread's state on that thread and rethrows the
// exception of the first failing task; sweeps and switch points are the same
// bit for bit on any number of threads, in double, CLN floats and exact
// rationals, and the threaded double sweep agrees with the threaded exact one.
// This executable is small on purpose: it is the one to run under
// ThreadSanitizer (-DSUPERBALL_SANITIZE=thread).
#include <gtest/gtest.h>

#include <cln/rational.h>
#include <cln/rational_io.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "superball/cases/error.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/numeric/parallel.hpp"
#include "superball/numeric/problem.hpp"
#include "superball/numeric/sweep.hpp"

namespace {

using namespace superball;
using cln::cl_RA;

const std::string kScenes = std::string(SUPERBALL_CASES_DIR) + "/scenes/";
const int kThreads[] = {1, 2, 3, 8};

std::uint64_t bits_of(double x) {
  std::uint64_t b = 0;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

TEST(ParallelMap, ResultsInTaskOrderOnAnyNumberOfThreads) {
  for (int threads : {0, 1, 2, 3, 8}) {
    for (std::size_t count : {0u, 1u, 2u, 1000u}) {
      const auto r = numeric::parallel_map(count, threads, [] { return 0; }, [](int&, std::size_t i) { return i * i; });
      ASSERT_EQ(r.size(), count);
      for (std::size_t i = 0; i < count; ++i) EXPECT_EQ(r[i], i * i) << "threads " << threads << ", task " << i;
    }
  }
}

TEST(ParallelMap, EachThreadBuildsAndKeepsItsOwnState) {
  struct State {
    std::thread::id owner = std::this_thread::get_id();
    cl_RA sum = 0;  // a CLN object that only its thread touches
  };
  for (int threads : kThreads) {
    const auto r = numeric::parallel_map(200, threads, [] { return State{}; }, [](State& s, std::size_t i) {
      EXPECT_EQ(s.owner, std::this_thread::get_id());
      s.sum = s.sum + cl_RA(static_cast<long>(i)) / 3;
      return std::make_pair(s.owner, numeric::to_string(cl_RA(static_cast<long>(i)) / 3));
    });
    std::set<std::thread::id> owners;
    for (std::size_t i = 0; i < r.size(); ++i) {
      owners.insert(r[i].first);
      EXPECT_EQ(r[i].second, numeric::to_string(cl_RA(static_cast<long>(i)) / 3));
    }
    EXPECT_LE(owners.size(), static_cast<std::size_t>(threads));
  }
}

TEST(ParallelMap, RethrowsTheExceptionOfTheFirstFailingTask) {
  for (int threads : kThreads) {
    try {
      numeric::parallel_map(500, threads, [] { return 0; }, [](int&, std::size_t i) {
        if (i == 37 || i == 38 || i == 400) throw std::runtime_error("task " + std::to_string(i));
        return i;
      });
      ADD_FAILURE() << "no exception with " << threads << " threads";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "task 37") << threads << " threads";
    }
  }
}

TEST(InOrder, DeliversEveryResultInOrderOnTheCallingThreadWithFewWaiting) {
  for (int threads : kThreads) {
    std::atomic<int> running{0}, most{0};
    std::size_t next = 0, waiting_most = 0;
    std::atomic<std::size_t> computed{0};
    const std::thread::id caller = std::this_thread::get_id();
    numeric::in_order(
        300, threads,
        [&](std::size_t i) {
          const int now = ++running;
          for (int m = most.load(); now > m && !most.compare_exchange_weak(m, now);) {
          }
          ++computed;
          if (i % 7 == 0) std::this_thread::sleep_for(std::chrono::microseconds(200));  // results finish out of order
          --running;
          return std::to_string(i);
        },
        [&](std::size_t i, std::string&& r) {
          EXPECT_EQ(std::this_thread::get_id(), caller);
          EXPECT_EQ(i, next) << threads << " threads";
          EXPECT_EQ(r, std::to_string(i));
          waiting_most = std::max(waiting_most, computed.load() - next);
          ++next;
        });
    EXPECT_EQ(next, 300u) << threads << " threads";
    EXPECT_LE(most.load(), threads) << "no more tasks at once than threads";
    // Done but not delivered: at most the window (2 x threads) and the tasks under way.
    EXPECT_LE(waiting_most, 3u * static_cast<std::size_t>(threads)) << threads << " threads";
  }
}

TEST(InOrder, AFailingTaskOrDeliveryEndsTheRunAfterTheResultsBeforeIt) {
  for (int threads : kThreads) {
    std::vector<std::size_t> got;
    try {
      numeric::in_order(
          500, threads,
          [](std::size_t i) {
            if (i == 37 || i == 38 || i == 400) throw std::runtime_error("task " + std::to_string(i));
            return i;
          },
          [&](std::size_t i, std::size_t r) {
            got.push_back(i);
            EXPECT_EQ(r, i);
          });
      ADD_FAILURE() << "no exception with " << threads << " threads";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "task 37") << threads << " threads";
    }
    EXPECT_EQ(got.size(), 37u) << threads << " threads";
    for (std::size_t i = 0; i < got.size(); ++i) EXPECT_EQ(got[i], i);
    // The delivery throws at result 20: nothing after it, the threads joined.
    std::size_t delivered = 0;
    try {
      numeric::in_order(500, threads, [](std::size_t i) { return i; }, [&](std::size_t i, std::size_t) {
        if (i == 20) throw std::logic_error("sink full");
        ++delivered;
      });
      ADD_FAILURE() << "no exception with " << threads << " threads";
    } catch (const std::logic_error& e) {
      EXPECT_STREQ(e.what(), "sink full");
    }
    EXPECT_EQ(delivered, 20u) << threads << " threads";
  }
}

TEST(ParallelMap, ThreadCountDefaultsToAllCores) {
  EXPECT_EQ(numeric::thread_count(3), 3);
  EXPECT_GE(numeric::thread_count(0), 1);
  EXPECT_EQ(numeric::thread_count(0), numeric::thread_count(-1));
}

/// The sweep of Fig. 7 (K34 from 0 to 20) on one thread and on several.
class SweepThreads : public ::testing::TestWithParam<numeric::Precision> {};

TEST_P(SweepThreads, SameBitsOnAnyNumberOfThreads) {
  const Scene scene = load_scene(kScenes + "paper-4.4-alpha2.toml");
  const Parameter k34 = Parameter::parse("K.3-4", scene);
  const auto values = numeric::linspace(0, 20, GetParam().kind == numeric::Precision::Kind::Double ? 401 : 41);
  const auto one = numeric::sweep(scene, k34, values, GetParam(), 1);
  ASSERT_EQ(one.size(), values.size());
  for (int threads : kThreads) {
    const auto many = numeric::sweep(scene, k34, values, GetParam(), threads);
    ASSERT_EQ(many.size(), one.size());
    for (std::size_t k = 0; k < one.size(); ++k) {
      SCOPED_TRACE("threads " + std::to_string(threads) + ", K34 = " + numeric::to_string(values[k]));
      EXPECT_TRUE(many[k].value == values[k]);
      EXPECT_EQ(many[k].closed, one[k].closed);
      EXPECT_EQ(many[k].status, one[k].status);
      ASSERT_EQ(many[k].velocities_after.size(), 4u);
      for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(bits_of(many[k].velocities_after[i]), bits_of(one[k].velocities_after[i]));
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Precisions, SweepThreads,
                         ::testing::Values(numeric::Precision::parse("double"), numeric::Precision::parse("digits:30"),
                                           numeric::Precision::parse("exact")),
                         [](const auto& info) { return info.param.kind == numeric::Precision::Kind::Digits ? std::string("digits")
                                                       : info.param.kind == numeric::Precision::Kind::Exact ? std::string("exact")
                                                                                                             : std::string("double"); });

TEST(SweepThreads, DoubleAgreesWithExactAndConservesMomentum) {
  const Scene scene = load_scene(kScenes + "paper-4.4-alpha2.toml");
  const Parameter k34 = Parameter::parse("K.3-4", scene);
  const auto values = numeric::linspace(0, 20, 81);
  const auto d = numeric::sweep(scene, k34, values, numeric::Precision::parse("double"), 2);
  const auto e = numeric::sweep(scene, k34, values, numeric::Precision::parse("exact"), 3);
  // Momentum before: Σ m_i U⁻_i, U⁻ = a·fall (every body but the obstacle falls at a).
  const auto exact = numeric::ExactScene::from(scene);
  const double a = std::sqrt(cln::double_approx(*exact.a_squared));
  double mass[4], before = 0;
  for (std::size_t i = 0; i < 4; ++i) {
    mass[i] = cln::double_approx(exact.mass[i]);
    before += mass[i] * cln::double_approx(exact.fall[i]) * a;
  }
  for (std::size_t k = 0; k < values.size(); ++k) {
    SCOPED_TRACE("K34 = " + numeric::to_string(values[k]));
    EXPECT_EQ(d[k].closed, e[k].closed);
    EXPECT_EQ(d[k].status, numeric::Status::Success);
    double momentum = 0, scale = 0;
    for (std::size_t i = 0; i < 4; ++i) {
      EXPECT_NEAR(d[k].velocities_after[i], e[k].velocities_after[i], 1e-12 * std::fabs(e[k].velocities_after[0]));
      momentum += mass[i] * e[k].velocities_after[i];
      scale += std::fabs(mass[i] * e[k].velocities_after[i]);
      if (i < 3) {  // no interpenetration
        EXPECT_GE(d[k].velocities_after[i] - d[k].velocities_after[i + 1], -1e-12);
      }
    }
    EXPECT_NEAR(momentum, before, 1e-12 * scale);
  }
}

TEST(SwitchPointsThreads, SameBracketsOnAnyNumberOfThreads) {
  const Scene scene = load_scene(kScenes + "paper-4.4-alpha2.toml");
  const Parameter k34 = Parameter::parse("K.3-4", scene);
  const auto points = numeric::sweep(scene, k34, numeric::linspace(0, 20, 41), numeric::Precision::parse("double"), 2);
  const auto one = numeric::switch_points(scene, k34, points, 64, 1);
  ASSERT_EQ(one.size(), 2u);
  for (int threads : kThreads) {
    const auto many = numeric::switch_points(scene, k34, points, 64, threads);
    ASSERT_EQ(many.size(), one.size()) << threads << " threads";
    for (std::size_t s = 0; s < one.size(); ++s) {
      EXPECT_TRUE(many[s].low == one[s].low && many[s].high == one[s].high) << threads << " threads";
      EXPECT_EQ(many[s].below, one[s].below);
      EXPECT_EQ(many[s].above, one[s].above);
    }
  }
}

TEST(SweepThreads, ABadRangeIsReportedTheSameOnAnyNumberOfThreads) {
  // K34 below 0 makes M indefinite; the minor named depends on the value.
  const Scene scene = load_scene(kScenes + "paper-4.4-alpha2.toml");
  const Parameter k34 = Parameter::parse("K.3-4", scene);
  const auto values = numeric::linspace(20, -20, 41);
  std::string first;
  for (int threads : kThreads) {
    try {
      numeric::sweep(scene, k34, values, numeric::Precision::parse("double"), threads);
      ADD_FAILURE() << "no error with " << threads << " threads";
    } catch (const InputError& e) {
      if (first.empty()) first = e.what();
      EXPECT_EQ(e.what(), first) << threads << " threads";
    }
  }
  // Refused before any value is solved, at the end of the range that fails (check_range()).
  std::string expected;
  try {
    numeric::check_range(scene, k34, values.front(), values.back());
  } catch (const InputError& e) {
    expected = e.what();
  }
  EXPECT_NE(expected.find("K.3-4 = -20: "), std::string::npos) << expected;
  EXPECT_EQ(first, expected);
}

}  // namespace
