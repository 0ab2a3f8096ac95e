#pragma once
/// \file reproduce.hpp
/// The options of a reproduction of the paper (`superball reproduce`): how
/// many points each of its runs draws, checked here once for every front.

#include "superball/verify/audit.hpp"
#include "superball/verify/explore.hpp"
#include "superball/verify/export.hpp"
#include "superball/verify/verification.hpp"
SUPERBALL_VERIFY_API_BEGIN

namespace superball::verify {

/// How much work the paper's reproduction does in each of its runs: the
/// audit of the printed conditions, the verification of the paper's cases and
/// the table of coupling patterns.  The defaults are those of each run's own
/// options.
struct ReproduceOptions {
  int samples = AuditOptions{}.samples;          ///< points tried per search of the audit (AuditOptions::samples)
  int verify_samples = VerifyOptions{}.samples;  ///< drawn points per ε of each verification run (VerifyOptions::samples)
  int explore_starts = ExploreOptions{}.starts;  ///< local searches per cell of the pattern table (ExploreOptions::starts)
  int threads = 0;                               ///< threads of the verification runs; 0: all cores

  /// Throws std::invalid_argument("ReproduceOptions::check(): NAME must be a
  /// whole number from LOW to HIGH, got V") naming the field as the fronts
  /// spell it (samples, verify_samples, explore_starts) unless samples is from
  /// 1 to max_audit_samples, verify_samples from 1 to max_verify_samples,
  /// explore_starts from 1 to max_starts; threads as numeric::check_threads().
  void check() const;

  /// The audit's options: AuditOptions with samples = #samples.
  AuditOptions audit() const;
  /// A verification run's options: VerifyOptions with samples =
  /// #verify_samples and threads = #threads.
  VerifyOptions verification() const;
  /// The pattern table's options: ExploreOptions with starts = #explore_starts.
  ExploreOptions exploration() const;
};

}  // namespace superball::verify

SUPERBALL_VERIFY_API_END
