#pragma once
/// \file drop.hpp
/// The whole drop of a scene with a [drop] table: the bodies, points on a
/// vertical line under gravity g, are released at their heights (the lowest
/// free body at drop_height over the obstacle, each other one `gap` above the
/// body below it), at rest unless the scene gives a velocity; every flight is
/// followed in closed form and every collision solved by the Frémond law
/// (numeric::solve) of the bodies that take part in it.
///
/// Who takes part.  By default (the touching view) the touching cluster: the
/// run of contacts closed at that instant (gap 0) that holds the closing
/// one, M restricted to it; the other bodies fly on.  With `[drop] distant =
/// true` every pair declared in M takes part in every collision, as the
/// paper's pseudo-potential φ(D((U⁺+U⁻)/2)) couples every pair of its
/// matrix M whatever their distance (K₁₄ couples ball 1 and the obstacle
/// through the stack): the colliding system is every body joined to the
/// closing contact through M's nonzero entries and the closed contacts; the
/// percussions of M act on all its pairs through X = D((U⁺+U⁻)/2) (paper
/// (6)–(12)), and impenetrability (the reaction P^reac ∈ ∂I₊(D_c(U⁺)) and
/// the choice "stays closed / opens") only on the contacts closed at that
/// instant (Problem::constrained); an open contact carries no reaction and
/// its relative velocity after takes any sign (the bodies are apart).
///
/// Events.  Between two free bodies the gap is linear in time (one gravity);
/// over a fixed obstacle, or a body resting on it, it is a parabola whose
/// root is taken in the stable form 2·gap/(√(D² + 2g·gap) − D).  The next
/// event is the earliest closing contact; contacts closing within
/// drop_tie_ulps units of roundoff of the time collide together (one
/// collision of their touching cluster), the order of the others is the
/// order of their times, and equal times are taken top to bottom, so the
/// run is deterministic.  A contact that closes later than the tie but
/// within drop_doubt_ulps is counted in DropResult::near_ties: its order is
/// decided by fewer than drop_doubt_ulps roundoffs, and running in
/// long double (64-bit significand) tells whether it changes the answer.
/// An order is certified when every other contact closes later than the
/// event's by more than the doubt bound: DropResult::orders_certified holds
/// when every order of the run is (no ties, no near ties); in exact
/// arithmetic every order is certified, a tie being an exact equality.
/// Precision auto (the overload taking a SolvePrecision) runs in double and,
/// when an order is not certified, again in long double, then in exact
/// rationals, and reports the last run with what double gave
/// (DropResult::escalated, DropResult::sequences_agree).
///
/// Rest.  A body (or a stack of touching bodies moving as one) bouncing
/// alone on the fixed obstacle has velocities in a
/// geometric sequence of ratio e (its law is linear); when nothing else can
/// touch it before the sum of the series and its apex is below
/// drop_rest_fraction of the release height, it comes to rest at
/// t_k + (2v_k/g)/(1 − e), stated as a DropRest, not bounced 10⁶ times.

#include <limits>
#include <string>
#include <vector>

#include "superball/cases/model.hpp"
#include "superball/numeric/precision.hpp"
#include "superball/numeric/export.hpp"
SUPERBALL_NUMERIC_API_BEGIN

namespace superball::numeric {

/// Contacts closing within this many units of roundoff of the event's time
/// scale (max(time, fall time of the top body)) collide together.
inline constexpr double drop_tie_ulps = 1024;
/// A contact closing after a tie but within this many units of roundoff of
/// the time scale is a near tie (DropResult::near_ties).
inline constexpr double drop_doubt_ulps = 1 << 20;
/// The bounces of a body alone on the fixed obstacle are followed one by one
/// until their apex is below this fraction of the top body's release height;
/// the rest of the geometric series is then summed in closed form.
inline constexpr double drop_rest_fraction = 1e-6;
/// A relative velocity below this many units of roundoff of the collision's
/// speed scale, after a collision, is a contact that stays closed.
inline constexpr double drop_closed_ulps = 1024;

/// One collision of a drop.
struct DropEvent {
  /// When it happens (s from the release).
  double time = 0;
  /// The contacts that closed at this instant ("2-3"), top to bottom.
  std::vector<std::string> contacts;
  ///@{
  /// The bodies of the touching cluster that collide (1-based, top and bottom).
  int first_body = 0, last_body = 0;
  ///@}
  /// The evolution case of the collision: the paper's name when the cluster
  /// is the whole stack of the paper's 4 bodies, else the closed contacts ("{3-4}").
  std::string case_name;
  /// The contacts of the cluster that stay closed after it ("3-4").
  std::vector<std::string> closed;
  /// The contacts of first_body … last_body that were open at the instant
  /// (distant view only: they carry no reaction), top to bottom.
  std::vector<std::string> apart;
  /// Whether every contact that did not close at this instant closed later
  /// by more than the doubt bound (drop_doubt_ulps; no tie, no near tie).
  bool order_certified = true;
  ///@{
  /// Every body's velocity before and after (m/s, upward positive) and height (m) at the event.
  std::vector<double> velocities_before, velocities_after, heights;
  ///@}
  ///@{
  /// The kinetic energy of every finite body before and after (J).
  double kinetic_energy_before = 0, kinetic_energy_after = 0;
  ///@}
  ///@{
  /// The momentum of the cluster's finite bodies before and after (kg m/s).
  double momentum_before = 0, momentum_after = 0;
  ///@}
};

/// A body's apex after its last collision (or its release when it had none).
struct DropApex {
  /// The body (1-based).
  int body = 0;
  /// Its height (m above the obstacle's release height).
  double height = 0;
  /// When (s).
  double time = 0;
};

/// A body that comes to rest on the fixed obstacle.
struct DropRest {
  /// The body (1-based).
  int body = 0;
  /// When (s).
  double time = 0;
  /// True when it is the sum of a geometric bounce sequence (Zeno), false
  /// when a collision left it at rest on the obstacle.
  bool accumulation = false;
  /// The ratio e of the bounce sequence (accumulation only).
  double ratio = 0;
};

/// The whole drop, in SI units.
struct DropResult {
  /// The arithmetic of the run reported, the one that decided the order of
  /// events ("double", "long-double").
  std::string precision;
  /// The arithmetic asked for: "auto", or #precision.
  std::string precision_asked;
  /// Whether every pair of M took part in every collision (`[drop] distant = true`).
  bool distant = false;
  /// Why the run ended: "apex" (the top body's first apex after its last
  /// collision), "until" (the scene's time), "rest" (no body moves any more),
  /// "no-more-events" (nothing can collide again), "max-events" (the scene's
  /// cap reached), "numerical-issue" (a collision's solve failed), "inexact"
  /// (exact arithmetic: the next event's time is an irrational square root).
  std::string end;
  /// The time the run ended (s).
  double end_time = 0;
  /// Gravity (m/s²).
  double g = 9.81;
  /// Whether the bottom body is a fixed obstacle.
  bool fixed_bottom = false;
  ///@{
  /// Every body's mass (∞ for a fixed obstacle), release height and release velocity.
  std::vector<double> masses, release_heights, release_velocities;
  ///@}
  /// The collisions, in time order.
  std::vector<DropEvent> events;
  /// Every free body's apex after its last collision, top to bottom.
  std::vector<DropApex> apexes;
  /// The bodies that came to rest on the fixed obstacle, in time order.
  std::vector<DropRest> rest;
  /// The top body's apex over its release height (its apexes entry / release_heights[0]; ∞ when released at 0).
  double top_apex_ratio = 0;
  /// Contacts that closed within drop_tie_ulps of an event's first contact,
  /// other than it, and collided with it.
  int ties = 0;
  /// Contacts that closed within drop_doubt_ulps but not drop_tie_ulps of an event.
  int near_ties = 0;
  /// Whether every order of events was certified: no ties and no near ties
  /// (every event's order_certified).
  bool orders_certified = true;
  /// Precision auto: whether the run in double had an order it could not
  /// certify, so that the drop was run again in long double, or exact (the run reported).
  bool escalated = false;
  /// When escalated: whether the runs in double and long double gave the
  /// same events (each one's contacts, bodies, case and the contacts that
  /// stay closed, in the same order) and ended the same way; true otherwise.
  bool sequences_agree = true;
  /// When escalated: the number of collisions of the run in double.
  int double_events = 0;
};

/// Whether a drop that ended by \p end (DropResult::end) ran the course its
/// scene asked for: false for "max-events" (the cap reached),
/// "numerical-issue" (a collision not solved) and "inexact" (exact
/// arithmetic met an event at an irrational time), the ends the command
/// exits 1 on.
SUPERBALL_NUMERIC_EXPORT bool drop_finished(const std::string& end);

/// The drop of \p scene (which must have a [drop] table) in \p precision:
/// double, long double, digits:N (MPFR) or exact (rationals, in units of
/// the landing speed when every body is released at rest over a fixed
/// obstacle, until an event's time is an irrational square root: end
/// "inexact").  Throws superball::InputError naming the scene
/// (M not positive semi-definite, no [drop] table) and
/// std::invalid_argument("drop(): ...") for a datum (g, drop_height, a gap, a velocity, a mass, until, the top release
/// height) that is not 0 and lies outside the arithmetic's window [2^−w, 2^w]
/// (w = safe_exponent<S>()).
DropResult drop(const Scene& scene, const Precision& precision);
/// The drop of \p scene in \p precision: a fixed one as drop(scene,
/// precision.fixed), or auto: in double, and when an order of events is not
/// certified (DropResult::orders_certified) again in long double, and when
/// that is not certified either, in exact rationals if they run the whole
/// drop (end not "inexact"); the last run returned, with escalated,
/// sequences_agree and double_events saying what double gave.  Throws as drop(scene, Precision), and
/// std::invalid_argument("drop(): ...") for an rtol (a drop's auto certifies
/// orders of events, not digits of velocities).
DropResult drop(const Scene& scene, const SolvePrecision& precision);

}  // namespace superball::numeric

SUPERBALL_NUMERIC_API_END
