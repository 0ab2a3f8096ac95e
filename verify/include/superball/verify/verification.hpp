#pragma once
/// \file verification.hpp
/// The derived conditions of one evolution case against exact solutions
/// (`superball verify`): parameter points of the paper's asymptotic regime
/// (§4: m₁ ~ ε, K₁ₙ ~ 1/ε, m_n ~ 1/ε for a finite obstacle), M positive
/// semi-definite, are solved exactly by the numeric backend (rationals) and
/// compared, at several ε, with the exact and the asymptotic conditions of
/// the case.  The exact conditions must agree at every point; the asymptotic
/// ones only in the limit ε → 0, so their agreement is tabulated over ε.
///
/// The points: a bulk drawn by RegimeSampler, then a boundary stage that
/// bisects, for each condition, segments between bulk points on opposite
/// sides of it, so that both sides of every condition and points within
/// 2^-boundary_bracket_bits (relative, along the segment) of its boundary
/// are present.  When the bulk has fewer than boundary_pairs points on one
/// side, a search moves points of the other side toward it (random moves of
/// coordinates within the regime, kept when they bring the condition's value
/// closer to that side); a side still empty is reported as not reached.
/// The run is a function of the options and the seed only: the work is cut
/// into blocks of fixed size, each with its own seed, merged in block order,
/// whatever the number of threads.
///
/// Its reports (text, JSON, a disagreement's scene comment) are
/// present/verification.hpp's.

#include <cln/rational.h>

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "superball/cases/model.hpp"
#include "superball/numeric/parallel.hpp"
#include "superball/symbolic/derivation.hpp"
#include "superball/verify/export.hpp"
SUPERBALL_VERIFY_API_BEGIN

namespace superball::verify {

/// Bisection along a segment between two points on opposite sides of a
/// condition stops when the bracket is at most 2^-boundary_bracket_bits of
/// the segment: both ends are then "near the boundary".
inline constexpr int boundary_bracket_bits = 20;
/// When a condition has fewer than boundary_pairs drawn points on one side,
/// up to this many random moves are tried per search for a point on it.
inline constexpr int reach_steps = 400;
/// Points of the bulk drawn per block of work (each block has its own seed).
inline constexpr int verify_block_points = 50;

/// The memory a drawn point of \p coordinates parameters holds until verify_case()'s
/// second stage, its outcome included: 64 bytes a coordinate and 128 more, an upper
/// estimate of what was measured (case 1 of α₂, 11 coordinates, 5 values of ε: the peak
/// grew by 684 bytes a drawn point between 20,000 and 80,000 points per ε).
constexpr double verify_point_bytes(int coordinates) { return 64.0 * coordinates + 128; }

/// What verify_case() does.
struct VerifyOptions {
  /// The values of ε (each in (0, 1)), exact; default 10⁻², …, 10⁻⁶.
  std::vector<cln::cl_RA> epsilons = {cln::cl_RA(1) / 100, cln::cl_RA(1) / 1000, cln::cl_RA(1) / 10000, cln::cl_RA(1) / 100000,
                                      cln::cl_RA(1) / 1000000};
  int samples = 4000;         ///< bulk points per ε (case 1 of §4.1: about 5 s of CPU time)
  int boundary_pairs = 20;    ///< segments bisected per condition and ε (fewer when a side has fewer bulk points)
  std::uint64_t seed = 1;     ///< of every pseudo-random point (reproducible)
  int threads = 0;            ///< worker threads; 0: std::thread::hardware_concurrency()
  /// Called with (points evaluated, points planned) as the run goes, from the
  /// worker threads one at a time (under a lock); may be empty.
  std::function<void(long long, long long)> progress;
  /// Where the blocks of work run, to spread one case over several processes
  /// (`mpirun -n P superball verify --case …`); empty: here, on `threads`.
  /// Called twice, for the drawn points and for the boundary stage, with a
  /// number of tasks T and a function computing task t (a group of blocks,
  /// solved on `threads`) as plain text; it must return the T texts in task
  /// order, in every process that calls verify_case() (each process then
  /// builds the boundary stage from the drawn points, and the result).  The
  /// result is the same, bit for bit, whoever runs the tasks.
  numeric::TaskRunner runner;

  /// Throws std::invalid_argument("VerifyOptions::check(): ...") naming the
  /// option (as Python's keywords and the command's options without "--"
  /// spell it): no epsilon, an epsilon not in (0, 1), samples not from 1 to
  /// max_verify_samples, boundary_pairs not from 0 to max_boundary_pairs,
  /// threads refused by numeric::check_threads().  verify_case() calls it.
  void check() const;
};

/// The most drawn points per ε (VerifyOptions::samples).
inline constexpr int max_verify_samples = 100000000;
/// The most segments bisected per condition and ε (VerifyOptions::boundary_pairs).
inline constexpr int max_boundary_pairs = 1000000;

/// A value of ε spelled as a scene file spells numbers ("1e-3", "0.001",
/// "1/1000"), exact; throws std::invalid_argument("OPTION: 'TEXT': what is
/// wrong") naming \p option ("epsilons", "epsilon").  Its range is the
/// options' check().
cln::cl_RA parse_epsilon(const std::string& option, const std::string& text);

/// Comma-separated values of ε ("1e-2,1e-4"), each read by parse_epsilon();
/// throws std::invalid_argument naming "epsilons" when there is none.
std::vector<cln::cl_RA> parse_epsilons(const std::string& text);

/// Blocks of drawn points per task of VerifyOptions::runner (400 points):
/// enough work to outweigh sending the points, enough tasks to share out.
inline constexpr std::size_t verify_task_blocks = 8;

/// A 2×2 confusion table: the conditions (hold / fail) against the truth.
struct Confusion {
  ///@{
  /// Conditions hold and truth true, hold and false, fail and true, fail and false.
  long long holds_true = 0, holds_false = 0, fails_true = 0, fails_false = 0;
  ///@}
  /// The number of points.
  long long total() const { return holds_true + holds_false + fails_true + fails_false; }
  /// The points where the conditions agree with the truth.
  long long agree() const { return holds_true + fails_false; }
};

/// One condition of the case (superball, evolution or contact; not PSD).
struct VerifiedCondition {
  /// The kind of the condition.
  symbolic::ConditionKind kind = symbolic::ConditionKind::Superball;
  /// What it is about, as in symbolic::Condition ("U1 > a", "2-3").
  std::string about;
  std::string exact_text;       ///< the form compared as exact (the finite-m_n one for a finite obstacle)
  /// The asymptotic form, as text.
  std::string asymptotic_text;
  /// Always / Never: the asymptotic form holds / fails at every admissible
  /// point, so one side of the condition vanishes as ε → 0 and may be out of reach.
  symbolic::Verdict asymptotic_verdict = symbolic::Verdict::Depends;
  /// "superball 1", "contact 2-3": its kind and what it is about.
  std::string name() const { return std::string(symbolic::to_string(kind)) + " " + about; }
};

/// The points of one ε seen by one condition.
struct ConditionTally {
  ///@{
  /// Points on each side: the condition holds, fails (for the exact solution of the case, forced).
  long long holds = 0, fails = 0;            ///< sides: the condition for the exact solution of the case (forced)
  ///@}
  ///@{
  /// Of them, ends of a bracket of this condition (width <= 2^-boundary_bracket_bits).
  long long near_holds = 0, near_fails = 0;  ///< of them, ends of a bracket of this condition (width <= 2^-boundary_bracket_bits)
  ///@}
  ///@{
  /// The points where the exact form, the asymptotic form agrees with the truth.
  long long exact_agree = 0, asymptotic_agree = 0;  ///< the forms that agree with that truth
  ///@}
  long long near_asymptotic_agree = 0;  ///< of the near points, those where the asymptotic form agrees
  /// The points seen: holds + fails.
  long long points() const { return holds + fails; }
};

/// The points of one stage at one ε.
struct Tally {
  long long points = 0;         ///< evaluated (solved or not)
  long long found = 0;          ///< of them, found by the search for a side short of points
  long long undrawn = 0;        ///< draws that found no admissible point
  long long unsolved = 0;       ///< points where the exact solver did not report success (not counted below)
  ///@{
  /// The conjunction of the exact, the asymptotic conditions against "case actual and U₁⁺ > a".
  Confusion exact, asymptotic;  ///< the conjunction of the conditions against "case actual and U₁⁺ > a"
  ///@}
  std::vector<ConditionTally> conditions;  ///< in the order of Verification::conditions
};

/// The results at one ε: the drawn points and the boundary stage apart (the
/// asymptotic forms are expected to disagree within O(ε) of a boundary).
struct EpsilonResult {
  /// The value of ε.
  cln::cl_RA epsilon;
  ///@{
  /// The drawn points and the boundary stage.
  Tally drawn, boundary;
  ///@}
  Tally all() const;  ///< both stages
};

/// A point where a form disagrees with the exact solution.
struct Disagreement {
  /// The index of the ε in Verification::epsilons.
  int epsilon_index = 0;
  bool near = false;               ///< from the boundary stage
  std::vector<std::pair<std::string, cln::cl_RA>> point;  ///< ASCII name → exact value
  Scene scene;                     ///< the collision at the point (`superball solve` reproduces it)
  std::string actual_case;         ///< the case of the exact unforced solution
  std::string quantity;            ///< "U1 - a = 3/7" of the exact unforced solution
  bool truth = false;              ///< case actual and U₁⁺ > a
  ///@{
  /// The conjunctions of the exact, the asymptotic forms at the point.
  bool exact = false, asymptotic = false;  ///< the conjunctions of the forms
  ///@}
  bool exact_form = false;         ///< an exact form disagrees (the conjunction or one condition): a defect
  std::vector<std::string> details;        ///< each condition form that disagrees, with the decided quantity
};

/// The verification of one case.
struct Verification {
  ///@{
  /// The case, the pattern, the obstacle and the scaling, as derive prints them.
  std::string case_name, pattern, obstacle, scaling;  ///< as derive prints them
  ///@}
  /// The case's conditions (PSD conditions left out).
  std::vector<VerifiedCondition> conditions;
  /// The results at each ε, in the order given.
  std::vector<EpsilonResult> epsilons;
  std::vector<Disagreement> disagreements;  ///< in run order (ε, then stage, then block)
  ///@{
  /// Points drawn per ε, boundary pairs sought per ε.
  int samples = 0, boundary_pairs = 0;
  ///@}
  /// The seed of the draws.
  std::uint64_t seed = 0;
  /// Whether the exact conditions agree with the exact solution at every point (conjunction and each one).
  bool exact_agrees() const;
  /// The points of condition \p c (index into `conditions`) over every ε, both stages.
  ConditionTally condition_total(std::size_t c) const;
};

/// Verify the case \p closed of \p deriver's pattern (paper §4) at each ε of
/// \p options: per point, the exact unforced solution (CollisionSolver<cl_RA>::
/// compute) decides the truth "the case is actual and U₁⁺ > a", and the exact
/// solution of the imposed case (compute_case) decides each condition alone
/// (condition_truth); both are compared with the derived exact forms (with a
/// finite obstacle, Condition::finite) and asymptotic forms.  Everything
/// symbolic happens in the calling thread; the workers get clones.  Throws
/// std::invalid_argument("verify_case(): ...") for bad options or a
/// pattern the sampler cannot handle (non-integer orders of ε).
Verification verify_case(const symbolic::Deriver& deriver, const ContactSet& closed, const VerifyOptions& options);

/// \p text of ε as a power of ten when it is one ("1e-3"), else the fraction.
std::string epsilon_name(const cln::cl_RA& epsilon);

}  // namespace superball::verify

SUPERBALL_VERIFY_API_END
