// symbolic::Workers (workers.hpp): tasks in forked worker processes, results
// in task order whatever the number of workers, a task's exception thrown
// again in the parent with its type and message, a dead worker reported, an
// interrupt that stops the workers at once, and no worker left behind; and
// derive_cases() over them.
#include "superball/symbolic/workers.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <ctime>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace superball::symbolic {
namespace {

/// No child process is left: every worker was reaped.
bool no_children() { return ::waitpid(-1, nullptr, WNOHANG) < 0 && errno == ECHILD; }

std::vector<std::string> run(std::size_t count, int jobs, const Workers::Task& task) {
  std::vector<std::string> out;
  Workers workers(count, jobs, task);
  workers.run([&](std::size_t k, std::string&& s) {
    EXPECT_EQ(k, out.size());  // in task order
    out.push_back(std::move(s));
  });
  return out;
}

TEST(Workers, ResultsInTaskOrderWhateverTheNumberOfWorkers) {
  const pid_t parent = ::getpid();
  // Early tasks take longest, so later ones finish first in the workers.
  auto task = [&](std::size_t k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(k < 3 ? 30 - 10 * static_cast<int>(k) : 1));
    return "task " + std::to_string(k) + (::getpid() == parent ? " here" : " in a worker") + std::string(k * 10000, 'x');
  };
  for (int jobs : {0, 1, 2, 3, 8}) {
    const std::vector<std::string> out = run(12, jobs, task);
    ASSERT_EQ(out.size(), 12u);
    for (std::size_t k = 0; k < out.size(); ++k) {
      EXPECT_EQ(out[k].substr(0, out[k].find(' ', 5)), "task " + std::to_string(k));
      EXPECT_EQ(out[k].find(jobs == 0 ? " in a worker" : " here"), std::string::npos) << jobs;
      EXPECT_EQ(std::count(out[k].begin(), out[k].end(), 'x'), static_cast<long>(k * 10000)) << "a large result crosses whole";
    }
    EXPECT_TRUE(no_children()) << jobs;
  }
  EXPECT_TRUE(run(0, 4, task).empty());
}

TEST(Workers, EachTasksCpuIsMeasuredWhereItRan) {
  // Task 1 computes for at least 50 ms of this process's CPU; the others return at once.
  auto task = [](std::size_t k) {
    if (k == 1) {
      const std::clock_t start = std::clock();
      volatile double x = 0;
      while (std::clock() - start < CLOCKS_PER_SEC / 20) x = x + 1;
    }
    return std::to_string(k);
  };
  for (int jobs : {0, 1, 2}) {
    Workers workers(3, jobs, task);
    workers.run([](std::size_t, std::string&&) {});
    const std::vector<double>& cpu = workers.task_cpu_seconds();
    ASSERT_EQ(cpu.size(), 3u) << jobs << " workers";
    EXPECT_GE(cpu[1], 0.05) << jobs << " workers";
    EXPECT_LT(cpu[0], cpu[1]) << jobs << " workers";
    EXPECT_LT(cpu[2], cpu[1]) << jobs << " workers";
    const std::string line = task_cpu_summary(cpu, [](std::size_t k) { return "task " + std::to_string(k); });
    EXPECT_EQ(line.rfind("3 tasks, ", 0), 0u) << line;
    EXPECT_NE(line.find("), task 1"), std::string::npos) << line;
  }
}

TEST(Workers, ATaskExceptionComesBackWithItsTypeAndMessage) {
  auto failing = [](std::size_t k) -> std::string {
    if (k == 5) throw std::invalid_argument("bad input on task 5");
    if (k == 7) throw std::logic_error("internal error on task 7");
    return std::to_string(k);
  };
  for (int jobs : {0, 3}) {
    try {
      run(10, jobs, failing);
      ADD_FAILURE() << "no exception, jobs " << jobs;
    } catch (const std::invalid_argument& e) {
      EXPECT_STREQ(e.what(), "bad input on task 5");
    }
    EXPECT_TRUE(no_children()) << jobs;
  }
  auto logic = [](std::size_t k) -> std::string {
    if (k == 2) throw std::logic_error("internal error on task 2");
    return "";
  };
  EXPECT_THROW(run(4, 2, logic), std::logic_error);
  EXPECT_TRUE(no_children());
}

TEST(Workers, TheFirstFailureInTaskOrderIsReportedWhateverTheTiming) {
  // Task 1 fails late, task 2 (and a dying worker on task 3) at once: what
  // is reported is task 1's failure, after task 0 was delivered, as when the
  // tasks run one after the other here.
  const pid_t parent = ::getpid();
  auto failing = [&](std::size_t k) -> std::string {
    if (k == 1) {
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      throw std::invalid_argument("task 1 failed late");
    }
    if (k == 2) throw std::logic_error("task 2 failed at once");
    if (k == 3 && ::getpid() != parent) ::raise(SIGKILL);
    return std::to_string(k);
  };
  for (int jobs : {0, 1, 2, 4}) {
    std::vector<std::size_t> delivered;
    Workers workers(8, jobs, failing);
    try {
      workers.run([&](std::size_t k, std::string&&) { delivered.push_back(k); });
      ADD_FAILURE() << "no exception, jobs " << jobs;
    } catch (const std::invalid_argument& e) {
      EXPECT_STREQ(e.what(), "task 1 failed late") << jobs;
    }
    EXPECT_EQ(delivered, std::vector<std::size_t>{0}) << jobs;
  }
  EXPECT_TRUE(no_children());
}

TEST(Workers, AWorkerThatDiesIsReportedWithItsTask) {
  const pid_t parent = ::getpid();
  auto dying = [&](std::size_t k) -> std::string {
    if (k == 3 && ::getpid() != parent) ::raise(SIGKILL);
    return std::to_string(k);
  };
  try {
    run(6, 2, dying);
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("worker for task 4 died: signal 9"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(no_children());
}

TEST(Workers, ADeliverThatThrowsStopsTheWorkers) {
  Workers workers(20, 3, [](std::size_t k) { return std::to_string(k); });
  EXPECT_THROW(workers.run([](std::size_t k, std::string&&) {
    if (k == 4) throw std::runtime_error("disk full");
  }),
               std::runtime_error);
  EXPECT_TRUE(no_children());
}

TEST(Workers, ATaskErrorComesBackWithItsCode) {
  auto failing = [](std::size_t k) -> std::string {
    if (k == 2) throw TaskError(3, "out.json: No space left on device");
    return std::to_string(k);
  };
  for (int jobs : {0, 2}) {
    try {
      run(5, jobs, failing);
      ADD_FAILURE() << "no exception, jobs " << jobs;
    } catch (const TaskError& e) {
      EXPECT_EQ(e.code(), 3) << jobs;
      EXPECT_STREQ(e.what(), "out.json: No space left on device") << jobs;
    }
  }
  EXPECT_TRUE(no_children());
}

TEST(Workers, AnInterruptStopsTheWorkersAtOnce) {
  // Each task would take 60 s: the interrupt, asked for after 300 ms, ends
  // the run within a few poll intervals, with the workers killed and reaped.
  const pid_t parent = ::getpid();
  auto slow = [&](std::size_t k) -> std::string {
    if (::getpid() != parent) std::this_thread::sleep_for(std::chrono::seconds(60));
    return std::to_string(k);
  };
  for (std::size_t count : {1u, 4u}) {
    Workers workers(count, 2, slow);
    const auto start = std::chrono::steady_clock::now();
    auto interrupted = [&] { return std::chrono::steady_clock::now() - start > std::chrono::milliseconds(300); };
    std::vector<std::size_t> delivered;
    EXPECT_THROW(workers.run([&](std::size_t k, std::string&&) { delivered.push_back(k); }, interrupted), Interrupted);
    const auto took = std::chrono::steady_clock::now() - start;
    EXPECT_LT(took, std::chrono::seconds(10)) << count;
    EXPECT_TRUE(delivered.empty());
    EXPECT_TRUE(no_children()) << count;
  }
  // In this process the interrupt is seen between tasks.
  Workers here(5, 0, [](std::size_t k) { return std::to_string(k); });
  std::vector<std::size_t> delivered;
  EXPECT_THROW(here.run([&](std::size_t k, std::string&&) { delivered.push_back(k); }, [&] { return delivered.size() == 2; }), Interrupted);
  EXPECT_EQ(delivered, (std::vector<std::size_t>{0, 1}));
}

TEST(Workers, AWorkerIgnoresSigint) {
  // Ctrl-C reaches every process of the terminal's group: the workers go on,
  // and it is this process (its interrupt hook) that decides.
  const pid_t parent = ::getpid();
  auto task = [&](std::size_t k) -> std::string {
    if (::getpid() != parent) {
      ::raise(SIGINT);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return std::to_string(k);
  };
  EXPECT_EQ(run(4, 2, task), (std::vector<std::string>{"0", "1", "2", "3"}));
  EXPECT_TRUE(no_children());
}

TEST(DeriveCases, TheSameResultsInCaseOrderWhateverTheWorkers) {
  const Deriver deriver(Pattern::nearest_and_next_nearest(4), Obstacle::Infinite);
  std::vector<ContactSet> cases;
  for (std::uint64_t mask = 0; mask < 8; ++mask) cases.push_back(ContactSet::from_mask(mask, 4));
  auto write = [](std::size_t k, const Derivation& d) { return std::to_string(k) + " " + d.case_name + ": " + d.conditions.front().about; };
  std::vector<std::string> first;
  for (int jobs : {0, 1, 3}) {
    std::vector<std::string> out;
    std::vector<std::size_t> progress;
    DeriveRun run;
    run.jobs = jobs;
    run.progress = [&](std::size_t done, std::size_t total) {
      EXPECT_EQ(total, 8u);
      progress.push_back(done);
    };
    derive_cases(deriver, cases, write, [&](std::size_t k, std::string&& s) {
      EXPECT_EQ(k, out.size());
      out.push_back(std::move(s));
    }, run);
    EXPECT_EQ(progress, (std::vector<std::size_t>{0, 1, 2, 3, 4, 5, 6, 7, 8})) << jobs;
    ASSERT_EQ(out.size(), 8u);
    EXPECT_EQ(out[0], "0 " + deriver.derive(cases[0]).case_name + ": U1 > a");
    if (first.empty()) first = out;
    EXPECT_EQ(out, first) << jobs;
    EXPECT_TRUE(no_children()) << jobs;
  }
}

/// Whether two derivations of one case are the same, expression by expression.
void expect_same(const Derivation& a, const Derivation& b) {
  const std::string what = a.case_name;
  EXPECT_TRUE(a.determinant.is_equal(b.determinant)) << what;
  ASSERT_EQ(a.velocities.size(), b.velocities.size()) << what;
  for (std::size_t i = 0; i < a.velocities.size(); ++i) {
    EXPECT_TRUE(a.velocities[i].numerator.is_equal(b.velocities[i].numerator)) << what << " U" << i + 1;
    EXPECT_TRUE(a.velocities[i].denominator.is_equal(b.velocities[i].denominator)) << what << " U" << i + 1;
  }
  for (std::size_t c = 0; c < a.reactions.size(); ++c) EXPECT_TRUE(a.reactions[c].numerator.is_equal(b.reactions[c].numerator)) << what;
  ASSERT_EQ(a.conditions.size(), b.conditions.size()) << what;
  for (std::size_t q = 0; q < a.conditions.size(); ++q) {
    const Condition &x = a.conditions[q], &y = b.conditions[q];
    EXPECT_EQ(x.about, y.about) << what;
    EXPECT_TRUE(x.exact.numerator.is_equal(y.exact.numerator)) << what << " " << x.about;
    EXPECT_TRUE(x.exact.denominator.is_equal(y.exact.denominator)) << what << " " << x.about;
    EXPECT_TRUE(x.asymptotic.numerator.is_equal(y.asymptotic.numerator)) << what << " " << x.about;
    EXPECT_EQ(x.exact.verdict, y.exact.verdict) << what << " " << x.about;
    EXPECT_EQ(x.proof, y.proof) << what << " " << x.about;
    EXPECT_EQ(x.exact.readable.has_value(), y.exact.readable.has_value()) << what << " " << x.about;
    EXPECT_EQ(x.exact.eliminated.has_value(), y.exact.eliminated.has_value()) << what << " " << x.about;
  }
  EXPECT_EQ(a.named.size(), b.named.size()) << what;
  EXPECT_EQ(a.elimination.has_value(), b.elimination.has_value()) << what;
  EXPECT_EQ(a.check, b.check) << what;
  EXPECT_EQ(a.actual, b.actual) << what;
}

TEST(DeriveCases, ACaseFinishedFromItsPreparedWorkIsTheSameDerivation) {
  // Finite obstacle: {} and the four cases of one closed contact are split (five free clusters, four).
  const Deriver deriver(Pattern::nearest_and_next_nearest(5), Obstacle::Finite);
  int split = 0;
  for (std::uint64_t mask = 0; mask < 16; ++mask) {
    const ContactSet c = ContactSet::from_mask(mask, 5);
    if (!split_case(deriver, c)) continue;
    ++split;
    expect_same(deriver.derive(c), deriver.derive(c, deriver.prepare(c)));
  }
  EXPECT_EQ(split, 5);
  EXPECT_FALSE(split_case(deriver, ContactSet::from_mask(3, 5)));  // two contacts closed: one stage
}

TEST(DeriveCases, PreparedWorkOfAnotherCaseOrTruncatedIsRefused) {
  const Deriver deriver(Pattern::nearest_and_next_nearest(5), Obstacle::Infinite);
  const ContactSet none = ContactSet::from_mask(0, 5), one = ContactSet::from_mask(1, 5);
  const std::string text = deriver.prepare(none);
  EXPECT_THROW(deriver.derive(one, text), std::invalid_argument);
  for (std::size_t keep : {std::size_t{5}, text.size() / 2, text.size() - 1 - 6})  // cut in the tag, in a polynomial, in the proofs
    EXPECT_THROW(deriver.derive(none, text.substr(0, keep)), std::invalid_argument) << keep;
}

/// Every case of \p n bodies, in mask order, and their indices (all to do).
std::pair<std::vector<ContactSet>, std::vector<std::size_t>> every_case(int n) {
  std::pair<std::vector<ContactSet>, std::vector<std::size_t>> out;
  for (std::uint64_t mask = 0; mask < (std::uint64_t{1} << (n - 1)); ++mask) {
    out.first.push_back(ContactSet::from_mask(mask, n));
    out.second.push_back(mask);
  }
  return out;
}

TEST(DeriveCases, APreparedCaseInPartsJoinsToTheWholeByteForByte) {
  // Finite obstacle: {} has five free clusters (three parts), the cases of one closed contact four (one).
  const Deriver deriver(Pattern::nearest_and_next_nearest(5), Obstacle::Finite);
  const ContactSet none = ContactSet::from_mask(0, 5);
  EXPECT_EQ(prepare_parts(deriver, none), 3);
  EXPECT_EQ(prepare_parts(deriver, ContactSet::from_mask(1, 5)), 1);
  const std::string whole = deriver.prepare(none);
  for (int pieces : {1, 2, 3, 5}) {
    std::vector<std::string> parts;
    for (int k = 0; k < pieces; ++k) parts.push_back(deriver.prepare(none, k, pieces));
    EXPECT_EQ(Deriver::join_prepared(parts), whole) << pieces;
    if (pieces > 1) {
      EXPECT_LT(parts[1].size(), 200u) << "only part 0 carries the solution";
    }
  }
}

TEST(DeriveCases, PartsOutOfPlaceOrOfAnotherCaseAreRefused) {
  const Deriver deriver(Pattern::nearest_and_next_nearest(5), Obstacle::Finite);
  const ContactSet none = ContactSet::from_mask(0, 5), one = ContactSet::from_mask(1, 5);
  for (const auto& [piece, pieces] : std::vector<std::pair<int, int>>{{2, 2}, {-1, 2}, {0, 0}, {0, -3}})
    EXPECT_THROW(deriver.prepare(none, piece, pieces), std::invalid_argument) << piece << " of " << pieces;
  const std::string a = deriver.prepare(none, 0, 2), b = deriver.prepare(none, 1, 2);
  EXPECT_THROW(Deriver::join_prepared({}), std::invalid_argument);
  EXPECT_THROW(Deriver::join_prepared({b, a}), std::invalid_argument);                              // out of order
  EXPECT_THROW(Deriver::join_prepared({a, deriver.prepare(one, 1, 2)}), std::invalid_argument);     // another case
  EXPECT_THROW(Deriver::join_prepared({a, deriver.prepare(none, 1, 3)}), std::invalid_argument);    // parts of three
  EXPECT_THROW(Deriver::join_prepared({a, b.substr(0, b.size() - 1)}), std::invalid_argument);      // truncated
  EXPECT_THROW(Deriver::join_prepared({a.substr(0, 12), b}), std::invalid_argument);                 // not prepared work
  EXPECT_THROW(Deriver::join_prepared({a, a}), std::invalid_argument);                              // part 0 twice
}

TEST(DeriveCases, TheLargestCasesArePreparedInPartsOverTheWorkers) {
  const Deriver deriver(Pattern::nearest_and_next_nearest(5), Obstacle::Finite);
  const auto [cases, all] = every_case(5);
  std::vector<double> cpu;
  std::vector<std::string> prepared;
  std::vector<std::pair<std::size_t, std::size_t>> seen;
  const std::vector<std::size_t> first =
      prepare_todo(deriver, cases, all, 2, prepared, {}, [&](std::size_t done, std::size_t total) { seen.emplace_back(done, total); }, &cpu);
  EXPECT_EQ(first, (std::vector<std::size_t>{0, 1, 2, 4, 8}));
  EXPECT_EQ(cpu.size(), 7u);  // {} in three parts, the four others in one
  EXPECT_EQ(seen, (std::vector<std::pair<std::size_t, std::size_t>>{{0, 5}, {1, 5}, {2, 5}, {3, 5}, {4, 5}, {5, 5}}));  // by case
  for (std::size_t k : first) EXPECT_EQ(prepared[k], deriver.prepare(cases[k])) << k;
  expect_same(deriver.derive(cases[0]), deriver.derive(cases[0], prepared[0]));
  EXPECT_TRUE(no_children());
}

TEST(DeriveCases, TheLargestCasesArePreparedInAFirstStageOnlyWithSeveralWorkers) {
  const Deriver deriver(Pattern::nearest_and_next_nearest(5), Obstacle::Infinite);
  const auto [cases, all] = every_case(5);
  std::vector<double> cpu;
  std::vector<std::string> one;
  int calls = 0;
  auto count = [&](std::size_t, std::size_t) { ++calls; };
  EXPECT_TRUE(prepare_todo(deriver, cases, all, 1, one, {}, count, &cpu).empty());
  EXPECT_EQ(one.size(), cases.size());
  EXPECT_TRUE(std::all_of(one.begin(), one.end(), [](const std::string& t) { return t.empty(); }));
  EXPECT_EQ(calls, 0);  // nothing prepared: no progress
  std::vector<std::string> two;
  EXPECT_EQ(prepare_todo(deriver, cases, all, 2, two, {}, count, &cpu), std::vector<std::size_t>{0});  // {}: four free clusters, the others three at most
  ASSERT_EQ(cpu.size(), 1u);
  EXPECT_EQ(calls, 2);
  EXPECT_EQ(two[0], deriver.prepare(cases[0]));
  for (std::size_t k = 1; k < two.size(); ++k) EXPECT_TRUE(two[k].empty()) << k;
  EXPECT_TRUE(no_children());
}

TEST(DeriveCases, OnlyTheCasesStillToDoArePreparedAndPutAtTheirIndex) {
  // Finite obstacle: {} and the four cases of one closed contact are split; a run (a checkpoint) has {} and {2-3} already.
  const Deriver deriver(Pattern::nearest_and_next_nearest(5), Obstacle::Finite);
  std::vector<ContactSet> cases;
  std::vector<std::size_t> todo;
  for (std::uint64_t mask = 0; mask < 16; ++mask) {
    cases.push_back(ContactSet::from_mask(mask, 5));
    if (mask != 0 && mask != 2) todo.push_back(mask);
  }
  std::vector<std::string> prepared(cases.size());
  prepared[3] = "kept";  // an entry not prepared is left as it is
  std::vector<std::pair<std::size_t, std::size_t>> seen;
  std::vector<double> cpu;
  const std::vector<std::size_t> first =
      prepare_todo(deriver, cases, todo, 3, prepared, {}, [&](std::size_t done, std::size_t total) { seen.emplace_back(done, total); }, &cpu);
  EXPECT_EQ(first, (std::vector<std::size_t>{1, 4, 8}));
  EXPECT_EQ(seen, (std::vector<std::pair<std::size_t, std::size_t>>{{0, 3}, {1, 3}, {2, 3}, {3, 3}}));
  EXPECT_EQ(cpu.size(), 3u);
  ASSERT_EQ(prepared.size(), cases.size());
  for (std::size_t k = 0; k < cases.size(); ++k) {
    if (k == 1 || k == 4 || k == 8)
      EXPECT_EQ(prepared[k], deriver.prepare(cases[k])) << k;
    else
      EXPECT_EQ(prepared[k], k == 3 ? "kept" : "") << k;
  }
  // What the second stage's workers make of it is the one-stage derivation.
  expect_same(deriver.derive(cases[4]), deriver.derive(cases[4], prepared[4]));
  EXPECT_TRUE(no_children());
  // An interrupt stops the stage: nothing more is delivered.
  std::vector<std::string> none;
  EXPECT_THROW(prepare_todo(deriver, cases, todo, 2, none, [] { return true; }), Interrupted);
  EXPECT_TRUE(no_children());
}

}  // namespace
}  // namespace superball::symbolic
