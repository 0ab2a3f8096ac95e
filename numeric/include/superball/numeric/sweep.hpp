#pragma once
/// \file sweep.hpp
/// Solutions along one parameter of a scene, and the parameter values where
/// the evolution case changes (paper §4.4, Fig. 7).

#include <cln/rational.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "superball/cases/parameter.hpp"
#include "superball/numeric/collision.hpp"
#include "superball/numeric/drop.hpp"
#include "superball/numeric/parallel.hpp"
#include "superball/numeric/precision.hpp"
#include "superball/numeric/export.hpp"
SUPERBALL_NUMERIC_API_BEGIN

namespace superball::numeric {

/// \p steps equally spaced exact values from \p from to \p to, ends
/// included (steps >= 2): x_k = from + (to − from)·k/(steps − 1), as
/// from + step·k.  The values of linspace() and of a map's Axis.
class Grid {
 public:
  /// The grid of \p steps values from \p from to \p to (steps >= 2, not checked: linspace() checks).
  Grid(const cln::cl_RA& from, const cln::cl_RA& to, int steps) : from_(from), step_((to - from) / (steps - 1)) {}
  /// x_k.
  cln::cl_RA operator()(int k) const { return from_ + step_ * k; }

 private:
  cln::cl_RA from_, step_;
};

/// `steps` equally spaced exact values from \p from to \p to, ends included
/// (steps >= 2): x_k of Grid(from, to, steps).  Only x_k for k in
/// [first, first + count) when \p count >= 0 (a chunk of a long sweep, made
/// without the others); throws std::invalid_argument when that is not inside
/// 0 … steps − 1.
std::vector<cln::cl_RA> linspace(const cln::cl_RA& from, const cln::cl_RA& to, int steps, int first = 0, int count = -1);

/// \p scene with \p parameter set to the exact \p value, through
/// Parameter::set() (the scene loader's checks; throws InputError).
Scene with_value(const Scene& scene, const Parameter& parameter, const cln::cl_RA& value);

/// Refuse, before anything is solved, a range of \p parameter from \p from to
/// \p to that holds an inadmissible value: each end is set through
/// Parameter::set() (the scene loader's checks: g > 0, drop_height >= 0,
/// fall_speed >= 0, mass > 0, …) and checked by ExactScene::from() (M
/// positive semi-definite, no contact opening before the collision).
///
/// The ends suffice: along one parameter every check admits an interval.
/// The loader's are signs of the value; M(p) = M₀ + p·E is positive
/// semi-definite on an interval (the PSD cone is convex); the velocities
/// before the collision U⁻ are affine in a velocity or in the fall speed a,
/// and a = sqrt(2 g h) is monotone in g and in h, so each D_c(U⁻) <= 0 holds
/// on an interval.  Throws InputError("ORIGIN: KEY = VALUE: what is wrong").
void check_range(const Scene& scene, const Parameter& parameter, const cln::cl_RA& from, const cln::cl_RA& to);

/// One point of a sweep: the parameter value, the solution in the chosen
/// arithmetic, with velocities already multiplied by the velocity unit and
/// converted to double, and the case.
struct SweepPoint {
  /// The parameter value (exact).
  cln::cl_RA value;
  /// U⁺, multiplied by the velocity unit, in double.
  std::vector<double> velocities_after;
  /// The evolution case.
  ContactSet closed;
  /// The solve's status.
  Status status = Status::Success;
};

/// Solve \p scene at each of \p values of \p parameter in \p precision,
/// on \p threads threads (0: all cores; parallel.hpp).  Each point is solved
/// on its own from the scene, so the result does not depend on \p threads,
/// bit for bit.  When \p parameter is an entry of M and the precision double
/// or long double, each thread converts the scene once and sets only that
/// entry per value: the same problem as converting the value's scene, bit
/// for bit, at a fraction of the cost.  The smallest and largest of \p values pass check_range()
/// first (throws InputError), so every value solved is admissible; no value,
/// or \p threads refused by check_threads(), throws std::invalid_argument,
/// and so does a scene with a [drop] table (refuse_drop(); drop_sweep()
/// sweeps drops), here and in sweep_marking_psd(), label_changes() and
/// switch_points().
std::vector<SweepPoint> sweep(const Scene& scene, const Parameter& parameter, const std::vector<cln::cl_RA>& values,
                              const Precision& precision, int threads = 1);

/// The most values sweep_marking_psd() solves by one call of sweep(): the
/// library's per-value results (a few hundred bytes each) held at once.
inline constexpr std::size_t sweep_chunk_values = std::size_t{1} << 16;

/// sweep() that marks the values where M is not positive semi-definite
/// instead of refusing the range, as a map marks its points (Python's
/// sweep; the command's `sweep`, which prints rows as it goes, refuses).
/// M's verdict at each value is psd_along()'s, exact.  Before anything is
/// solved: \p threads passes check_threads(), there is a value
/// (std::invalid_argument otherwise), M is PSD at one of them at least
/// (else InputError("ORIGIN: M is not positive semi-definite at any value of
/// the sweep (KEY from LOW to HIGH): nothing to solve")), and check_range()
/// passes from the smallest to the largest PSD value.  Then the PSD values
/// are solved as sweep() solves them, sweep_chunk_values at a time, and
/// deliver(k, point) is called for each in increasing k (the index into
/// \p values), here; progress(done, total) (may be empty), in PSD values,
/// before each chunk and at the end.  Either may throw to stop the sweep.
/// The points are those of sweep() over the PSD values alone, bit for bit.
/// Returns the verdict at each value.  With a \p runner (a checkpoint,
/// parallel.hpp), each chunk is one of its tasks, its points sent as
/// write_sweep_points() text, and \p progress is the runner's business.
std::vector<bool> sweep_marking_psd(const Scene& scene, const Parameter& parameter, const std::vector<cln::cl_RA>& values,
                                    const Precision& precision, int threads,
                                    const std::function<void(std::size_t, const SweepPoint&)>& deliver,
                                    const std::function<void(std::size_t, std::size_t)>& progress = {}, const TaskRunner& runner = {});

/// The points of a sweep as text, one line each: "U1 … Un CLOSED STATUS"
/// (each velocity in 17 significant digits, which read back to the same
/// double; CLOSED the closed contacts "2-3,3-4" or "none"; STATUS as
/// to_string(Status)).  The values are not written: the reader knows them.
std::string write_sweep_points(const std::vector<SweepPoint>& points);

/// Reads back write_sweep_points()' text of a scene of \p bodies bodies
/// (values left 0); std::invalid_argument("read_sweep_points(): a damaged
/// result (…)") when it is not that.
std::vector<SweepPoint> read_sweep_points(const std::string& text, int bodies);

/// What a map or a sweep keeps of one drop (a scene with a [drop] table,
/// drop()): its label, the sequence of its collisions, and its value, the
/// top body's apex ratio.
struct DropPoint {
  /// drop_label() of the run: equal sequences of collisions, equal labels.
  std::string label;
  /// DropResult::top_apex_ratio.
  double ratio = 0;
  /// The number of collisions.
  int events = 0;
  /// DropResult::end ("apex", "rest", "max-events", …).
  std::string end;
};

/// The label of a drop: its collisions in time order, each written
/// CONTACTS:CASE (the contacts that closed at that instant, then
/// DropEvent::case_name, e.g. "2-3:{}" or "1-2,2-3,3-4:3.3"), separated by
/// one space, a run of k > 1 equal collisions written once as TOKEN*k
/// ("3-4:{}*12"); "none" when there was no collision.  Canonical: two drops
/// have the same label exactly when their sequences of contacts and cases
/// are the same.
std::string drop_label(const DropResult& result);

/// The DropPoint of \p result.
DropPoint drop_point(const DropResult& result);

/// The drop of \p scene (with a [drop] table) at each of \p values of
/// \p parameter, in \p precision, on \p threads threads (0: all cores):
/// every value is its own run of drop() from the scene with the value
/// assigned, so each point is that of `superball drop` on the scene with
/// the value written in, bit for bit, whatever \p threads.  First the
/// smallest and the largest value are set through Parameter::set() (the
/// loader's checks: gap >= 0, drop_height > 0 over a fixed obstacle, …) and
/// dropped (drop()'s checks: M positive semi-definite, the precision
/// double or long double); along one parameter every check admits an
/// interval, so every value between passes.  Throws InputError
/// ("ORIGIN: KEY = VALUE: what is wrong") or std::invalid_argument as those
/// do, std::invalid_argument without a value, for a scene without [drop]
/// or for \p threads refused by check_threads().
std::vector<DropPoint> drop_sweep(const Scene& scene, const Parameter& parameter, const std::vector<cln::cl_RA>& values,
                                  const Precision& precision, int threads = 1);

/// Throws std::invalid_argument("WHAT: ORIGIN has a [drop] table: a map
/// or sweep of drops runs in one process …"): a sweep or map of drops is
/// not spread over MPI ranks, shards or a checkpoint (drop_map() with a
/// runner, the fronts' options).
[[noreturn]] void refuse_distributed_drop(const Scene& scene, const std::string& what);

/// Throws std::invalid_argument("WHAT: ORIGIN has a [drop] table: …")
/// when \p scene asks for a drop: \p what (switch_points(),
/// label_changes(), an overlay) bisects the exact solution of one
/// collision, which a drop, a sequence of collisions, does not have.
void refuse_drop(const Scene& scene, const std::string& what);

/// The exact solution (CLN rationals) of a scene at one parameter value.
struct ExactPoint {
  /// The scene at the value, as an exact problem.
  Problem<cln::cl_RA> problem;
  /// Its exact solution.
  Solution<cln::cl_RA> solution;
};
/// The exact solution of \p scene with \p parameter = \p value.
ExactPoint solve_exact_at(const Scene& scene, const Parameter& parameter, const cln::cl_RA& value);

/// A property of the exact solution that a bisection tracks (the case, "is
/// U1+ > a", …), as a label.
using Label = std::function<std::string(const ExactPoint&)>;

/// What a floating-point solve proves about the exact solution at one value
/// of a parameter (certify(), as `--precision auto` trusts it): the exact
/// evolution case, and the superball verdict U₁⁺ > |U₁⁻| when the certified
/// bound on U₁⁺ decides it.
struct ProvenPoint {
  /// The evolution case, certified.
  ContactSet closed;
  std::optional<bool> superball;  ///< nothing when |U₁⁺ − |U₁⁻|| is within the bound
};

/// The rounding allowed when a floating-point solve decides the superball
/// verdict (ProvenPoint), in units of the arithmetic's unit roundoff times
/// |U₁⁺| + |U₁⁻| + max_i |U_i⁺|, on top of the certified bound on U₁⁺: the
/// rounding of U₁⁻ into the arithmetic and of the comparison, with room.
inline constexpr double proven_verdict_rounding = 8;

/// A shortcut for a Label: the label of the exact solution, read off what a
/// floating-point solve proved, or nothing when that does not decide it.
/// Wherever it answers it must answer as the Label would on the exact solution.
using ProvenLabel = std::function<std::optional<std::string>(const ProvenPoint&)>;

/// How the labels of label_changes() were found: proven by a certified
/// double solve, by the exact check of a case met last, or by an exact solve.
struct LabelCounts {
  ///@{
  /// Labels found by a certified double solve, by the exact check of a case met last, by an exact solve.
  std::size_t in_double = 0, by_case = 0, solved = 0;
  ///@}
};

/// A change of label between two parameter values, bracketed by [low, high].
struct LabelChange {
  ///@{
  /// The bracket of the change, low < high.
  cln::cl_RA low, high;
  ///@}
  ///@{
  /// The label at low and at high.
  std::string below, above;
  ///@}
};

/// Locate every change of \p label between consecutive \p values (monotone,
/// ascending or descending) by bisection on the exact solution until the
/// bracket is narrower than 2^-bits of the step.  Where the midpoint's label
/// differs from both ends (a third label inside the bracket), both halves are
/// searched, so every change between two values of different labels is
/// found (changes that come back to the same label between two values are
/// not seen).  The result is in increasing parameter value, low < high, with
/// `below` the label at low and `above` the label at high, and the changes
/// chain: each one's `above` is the next one's `below`.  The values pass
/// check_range() first, as in sweep().  Throws std::invalid_argument
/// unless \p bits is from 1 to max_bits, \p threads passes check_threads()
/// and the values are strictly monotone.
/// The labels at \p values, then the bisections, run on \p threads threads
/// (0: all cores); with more than one, \p label is called on several threads
/// at once and must not share a CLN object between calls (no captured
/// cl_RA); the result does not depend on \p threads.
///
/// With \p proven, and when \p parameter is an entry of M (a K or a
/// coupling), each label is found without the exact solve where it can be:
/// first from a double solve (each thread converts the scene once and sets
/// only that entry, as sweep() does) whose case certify() proves and from
/// which \p proven reads the label; then, where double cannot decide (near
/// each change), by the two cases met last, checked exactly: a case that
/// holds with strict complementarity (every closed contact's reaction < 0,
/// every open one's gap > 0) is the exact solution's case.  Along the line
/// those signs are polynomials in the entry's value (degree at most 4 once
/// multiplied by the positive determinant of the case's reduced system), so
/// each case's are interpolated exactly once per call and checked at one
/// more value, and a check costs a few integer products.  Only where
/// neither decides is the scene solved exactly.  The midpoints are the same
/// exact rationals and each label is the exact one, so the result is the
/// same, bit for bit.  \p counts, when given, receives how the labels were
/// found.
std::vector<LabelChange> label_changes(const Scene& scene, const Parameter& parameter, const std::vector<cln::cl_RA>& values,
                                       const Label& label, int bits = 64, int threads = 1, const ProvenLabel& proven = {},
                                       LabelCounts* counts = nullptr);

/// A change of evolution case between two parameter values: the case is
/// `below` for values in [low, …) up to the switch and `above` after it;
/// high − low is the width left by the bisection.
struct SwitchPoint {
  ///@{
  /// The bracket of the switch, low < high.
  cln::cl_RA low, high;
  ///@}
  ///@{
  /// The case at low and at high.
  ContactSet below, above;
  ///@}
};

/// Most halvings of a bracket (`bits` of label_changes(), switch_points(), MapSettings).
inline constexpr int max_bits = 1024;

/// Locate every case change between consecutive \p values (at least two: else
/// std::invalid_argument) by bisection on
/// the exact solution (CLN rationals) until the bracket is narrower than
/// 2^-bits of the sweep step (default: 64 bits, beyond double precision),
/// on \p threads threads (0: all cores), as label_changes(): in increasing
/// parameter value, each switch starting in the case the previous one ended in.
std::vector<SwitchPoint> switch_points(const Scene& scene, const Parameter& parameter, const std::vector<cln::cl_RA>& values,
                                       int bits = 64, int threads = 1);
/// switch_points() at the values of \p points (the cases are found again, exactly).
std::vector<SwitchPoint> switch_points(const Scene& scene, const Parameter& parameter, const std::vector<SweepPoint>& points,
                                       int bits = 64, int threads = 1);

}  // namespace superball::numeric

SUPERBALL_NUMERIC_API_END
