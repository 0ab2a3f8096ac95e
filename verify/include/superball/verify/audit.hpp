#pragma once
/// \file audit.hpp
/// The paper's printed conditions (§4.1–§4.3) and claims in words against
/// the symbolic derivation, with concrete parameter points solved exactly by
/// the numeric backend.  The paper is data, not truth: each printed
/// condition is found identical to the exact condition, identical at the
/// asymptotic order, or different — and a "different" one comes with a
/// parameter point (M positive semi-definite, in the asymptotic regime) where
/// it disagrees with the exact solution while the derived condition agrees.
/// The audit's reports (text, JSON) are present/audit.hpp's.

#include <cln/rational.h>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "superball/cases/printed_conditions.hpp"
#include "superball/verify/space.hpp"
#include "superball/verify/export.hpp"
SUPERBALL_VERIFY_API_BEGIN

namespace superball::verify {

/// How the audit samples parameter points.
struct AuditOptions {
  cln::cl_RA epsilon = cln::cl_RA(1) / 1000;  ///< ε of the regime: m₁ = ε·m̃₁, K₁₄ = K̃₁₄/ε, others O(1)
  int samples = 20000;                        ///< points tried per search
  std::uint64_t seed = 1;                     ///< of the pseudo-random points (reproducible)

  /// Throws std::invalid_argument("AuditOptions::check(): ...") unless
  /// epsilon is in (0, 1) and samples from 1 to max_audit_samples (read
  /// ε with parse_epsilon("epsilon", text)).  audit_paper() calls it.
  void check() const;
};

/// The most points tried per search of the audit (AuditOptions::samples).
inline constexpr int max_audit_samples = 10000000;

/// A parameter point and what each side says there.
struct Witness {
  std::vector<std::pair<std::string, cln::cl_RA>> point;  ///< ASCII name → exact value (a included)
  std::string quantity;          ///< the numeric quantity decided, e.g. "R2_3 = -13/7" or "U1 - a = 1/9"
  std::string actual_case;       ///< the case the exact (unforced) numeric solution takes there
  bool printed = false;          ///< the printed condition holds
  bool numeric = false;          ///< the condition holds for the exact solution of the case (numeric backend)
  bool derived_exact = false;    ///< the derived exact condition holds
  bool derived_asymptotic = false;  ///< the derived asymptotic condition holds
};

/// How a printed condition compares with the derivation.
enum class Agreement { IdenticalExact, IdenticalAsymptotic, Different };
/// The agreement in words: "identical to the exact condition", "identical at the asymptotic order", "different".
const char* to_string(Agreement a);

/// A formula in text notation (Unicode) and in LaTeX (math mode without `$`,
/// or text mode with its formula in $…$ for a title), both printed from the
/// same expression (symbolic/format.hpp).
struct Formula {
  /// The formula in text (Unicode).
  std::string text;
  /// The same formula in LaTeX.
  std::string latex;
};

/// The audit of one printed condition.
struct ConditionAudit {
  /// The printed condition, as transcribed.
  PrintedCondition printed;
  /// How it compares with the derived condition.
  Agreement agreement = Agreement::Different;
  Formula title;                  ///< what the condition ensures, in words: "superball (U₁⁺ > a)", "velocity U₁⁺"
  Formula as_printed;             ///< the printed condition re-written in our notation
  Formula exact;                  ///< the derived exact condition (m₄ = ∞)
  Formula asymptotic;             ///< the derived asymptotic condition
  Formula printed_asymptotic;     ///< the dominant balance of the printed condition (empty for a velocity)
  std::vector<std::string> notes; ///< strictness differences, PSD look-alikes, transcription notes
  std::optional<Witness> witness; ///< Different: printed ≠ numeric there, derived = numeric
  int tried = 0;                  ///< points tried in the search
};

/// The audit of one claim in words.
struct ClaimAudit {
  /// The claim, as transcribed.
  PaperClaim claim;
  /// Whether the derivation supports the claim.
  bool supported = false;
  std::string verdict;                    ///< one line: what was shown
  std::vector<std::string> comparisons;   ///< per condition: same as the `like` pattern after renaming, or not
  Formula superball;                      ///< the derived exact superball condition of the claim's pattern
  std::string certificate;                ///< "impossible" claims: the proof, when found
  std::optional<Witness> example;         ///< a point with the case actual and U₁⁺ > a, when found
  /// The points drawn in search of an example.
  int tried = 0;
  int hits = 0;                           ///< points where the case was actual and U₁⁺ > a
};

/// The whole audit.
struct Audit {
  /// The options the audit ran with.
  AuditOptions options;
  /// Each printed condition's audit, in the transcription's order.
  std::vector<ConditionAudit> conditions;
  /// Each claim's audit, in the transcription's order.
  std::vector<ClaimAudit> claims;
};

/// Audit every printed condition and claim of \p data (paper §4.1–§4.3).
/// Throws std::invalid_argument("audit_paper(): ...") when an entry names an
/// unknown case, condition or symbol, or the scaling has non-integer orders.
Audit audit_paper(const PrintedConditions& data, const AuditOptions& options = {});

}  // namespace superball::verify

SUPERBALL_VERIFY_API_END
