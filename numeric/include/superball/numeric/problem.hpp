#pragma once
/// \file problem.hpp
/// The entry point of the numeric backend: a Scene checked and turned into
/// exact rationals (ExactScene), then into the scalar type of a solve
/// (`Problem<S>`).

#include <cln/rational.h>

#include <algorithm>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "superball/cases/model.hpp"
#include "superball/numeric/scalar.hpp"
#include "superball/numeric/export.hpp"
SUPERBALL_NUMERIC_API_BEGIN

namespace superball::numeric {

/// One declared entry of M: pairs (i, j) and (k, l), 0-based bodies.
template <class S>
struct Entry {
  ///@{
  /// The two pairs (i, j) and (k, l), 0-based bodies, i < j and k < l.
  int i, j, k, l;
  ///@}
  /// The coefficient.
  S value;
  /// True for a diagonal coefficient K_ij ((i, j) == (k, l)).
  bool diagonal() const { return i == k && j == l; }
  /// How far apart the bodies it couples are: max(j, l) − min(i, k).
  int span() const { return std::max(j, l) - std::min(i, k); }
};

/// A scene in exact rationals, checked.
///
/// Velocities before the collision are U⁻ = unit · u: when every body either
/// falls at −a or is given velocity 0, the unit is the fall speed
/// a = sqrt(2 g h) (possibly irrational; only a² is stored) and u ∈ {−1, 0}.
/// The collision is homogeneous of degree one in U⁻, so the solve runs on u
/// and the results scale by a.  Otherwise the unit is 1 and u = U⁻.
struct ExactScene {
  /// Where the scene came from (for messages).
  std::string origin;
  /// The number of bodies.
  int n = 0;
  bool fixed_bottom = false;             ///< body n has infinite mass
  std::vector<cln::cl_RA> mass;          ///< size n (the fixed body's entry is unused)
  /// The declared entries of M (0-based pairs).
  std::vector<Entry<cln::cl_RA>> entries;
  std::vector<cln::cl_RA> fall;          ///< coefficient of a in U⁻_i (−1 falls, 0 not)
  std::vector<cln::cl_RA> velocity;      ///< the constant part of U⁻_i
  std::optional<cln::cl_RA> a_squared;   ///< a², when the scene has a fall speed

  /// Check \p scene and convert it.  Throws superball::InputError naming the
  /// scene and what is wrong; the positive semi-definiteness of M is decided
  /// exactly (the message names a principal minor of M that is negative), and
  /// so is the sign of every adjacent contact's D_c(U⁻) = U⁻_i − U⁻_{i+1}:
  /// a contact opening before the collision (D_c(U⁻) > 0) is rejected, since
  /// the reaction's dissipation P^reac·D_c(U⁻)/2 (paper §3) is then not
  /// guaranteed >= 0 and the solve could create kinetic energy.
  static ExactScene from(const Scene& scene);
  /// What from() decides about M.
  enum class MCheck {
    PositiveSemidefinite,  ///< refuse a scene whose M is not positive semi-definite (InputError)
    Caller                 ///< leave it to the caller (positive_semidefinite()), e.g. a map that marks such points
  };
  /// from(), with the positive semi-definiteness of M checked or not (\p m);
  /// every other check is made.
  static ExactScene from(const Scene& scene, MCheck m);

  /// Whether U⁻ = a·u with u = fall (every explicit velocity is 0).
  bool homogeneous() const;
  /// The velocity unit squared: a² when homogeneous() and a exists, else 1.
  cln::cl_RA unit_squared() const;
  /// U⁻ in units of the unit, exact; nullopt when that needs an irrational a
  /// (non-homogeneous scene with irrational a).
  std::optional<std::vector<cln::cl_RA>> exact_u() const;
};

/// Powers of two that bring the data of a problem into the middle of the
/// range of its floating-point type.  The collision is invariant under
/// m → λm, M → λM, U⁻ → μU⁻ (equations (5): percussions and reactions scale
/// by λμ, velocities after by μ, energies by λμ²), so a problem solved with
/// λ = 2^−mass and μ = 2^−velocity gives the answer of the original one,
/// scaled back exactly, wherever that answer is representable.
struct Scaling {
  int mass = 0;      ///< masses and M were divided by 2^mass
  int velocity = 0;  ///< velocities were divided by 2^velocity
  /// Whether the magnitudes of the masses and of M, and those of the
  /// velocities, each span at most the safe window of the type (see
  /// safe_exponent()): otherwise no scaling fits them and products of the
  /// solve can overflow or underflow.
  bool fits = true;
  /// True when no scaling is applied (both exponents 0).
  bool identity() const { return mass == 0 && velocity == 0; }
};

/// A collision problem in scalar type S (velocities in units of the unit).
template <class S>
struct Problem {
  /// The number of bodies.
  int n = 0;
  /// Body n has infinite mass (a fixed obstacle).
  bool fixed_bottom = false;
  /// The masses, size n (the fixed body's entry is unused).
  std::vector<S> mass;
  /// The declared entries of M (0-based pairs).
  std::vector<Entry<S>> entries;
  /// The velocities before the collision in units of #unit, size n.
  std::vector<S> u;
  S unit = S(1);            ///< multiply velocities by this (a, or 1)
  bool unit_exact = true;   ///< false when the unit is irrational and S is exact (unit is then 1 here)
  int digits = 0;           ///< for CLN floats: the decimal digits
  /// False when S cannot hold the scene: some nonzero datum (a mass, an
  /// entry of M, a velocity or the unit) rounded to zero, to a subnormal
  /// number or to infinity.  Every solve of such a problem ends with
  /// Status::NumericalIssue (double and long double only; CLN types always
  /// hold the scene).
  bool in_range = true;
  /// Per adjacent contact c (bodies c and c+1, 0-based): whether
  /// impenetrability holds there, i.e. the contact is closed at the instant
  /// of the collision and may stay closed (reaction λ_c ≥ 0, gap D_c(U⁺) ≥ 0,
  /// λ_c·D_c(U⁺) = 0).  A contact that is not constrained is open at that
  /// instant (the two bodies are apart): no reaction and no sign condition
  /// on its gap, while M's percussions still act on its pair when M declares
  /// it (interactions at a distance: a drop with `distant = true`,
  /// numeric/drop.hpp).  Empty (the default): every contact is constrained,
  /// and every solver takes the path it always took.  Otherwise n−1 flags;
  /// the evolution cases are then enumerated over the constrained contacts
  /// only.
  std::vector<char> constrained;

  /// Whether contact \p c is constrained (see #constrained).
  bool constrained_contact(int c) const { return constrained.empty() || constrained[static_cast<std::size_t>(c)] != 0; }

  /// Convert \p scene to S.  Throws superball::InputError when S is exact and
  /// the scene needs an irrational number inside the solve.  A datum outside
  /// the range of S is not an error of the scene: in_range says so.
  static Problem from(const ExactScene& scene, int digits = 0);

  /// The same problem with masses and M multiplied by 2^−scaling.mass and
  /// velocities by 2^−scaling.velocity: exact in binary floating point (no
  /// datum leaves the range when the scaling comes from scaling_of()).
  Problem scaled(const Scaling& scaling) const;

  /// Misuse check at a solver's entry point: at least 2 bodies, one mass
  /// and one velocity per body, every entry of M on pairs i < j, k < l of
  /// bodies 0 … n−1, #constrained empty or one flag per contact.  Throws std::invalid_argument("<who>: ...").  Returns
  /// bandwidth(), found in the same pass over the entries.
  int check(const char* who) const;

  /// The bandwidth b of DᵀMD: the largest max(j, l) − min(i, k) over the
  /// entries (i-j, k-l) of M (0 when M is empty).  O(entries); assumes check().
  int bandwidth() const {
    int b = 0;
    for (const Entry<S>& e : entries) b = std::max(b, e.span());
    return b;
  }
};

/// The binary exponent w of the safe window [2^−w, 2^w] of a floating-point
/// type S: max_exponent / 4 (256 for double, 4096 for long double), so that
/// products of up to three data (the energies m·u²) and their sums stay
/// normal.  0 for the CLN types, whose exponent range no scene reaches (no
/// window, no scaling).
template <class S>
constexpr int safe_exponent() {
  if constexpr (std::is_floating_point<S>::value) {
    return std::numeric_limits<S>::max_exponent / 4;
  } else {
    return 0;
  }
}

/// The Scaling of \p p: the identity when every nonzero mass, entry of M and
/// velocity already lies in the safe window (so such problems are solved
/// bit for bit as given), else the powers of two nearest the geometric
/// middle of each group's magnitudes.  O(n + entries).
template <class S>
Scaling scaling_of(const Problem<S>& p);

/// Largest n CollisionSolver accepts: it stores n × n matrices, and a
/// falling stack that pivots on every contact takes 31 s of CPU in double at
/// this size, 78 s at 2048 (O(n³); docs/PERFORMANCE.md).  ExactScene::from
/// refuses a scene over it whose M is not banded, by the file's name.
inline constexpr int dense_solver_max_bodies = 1536;

/// The smallest principal minor check: nullopt when the symmetric matrix
/// \p M (size m) is positive semi-definite, else the indices of a principal
/// submatrix with a negative determinant and that determinant.
struct NegativeMinor {
  /// The 0-based indices of the principal submatrix.
  std::vector<int> indices;
  /// Its determinant (< 0).
  cln::cl_RA determinant;
};
/// A symmetric matrix by rows of its nonzero entries: row i maps column j to
/// M_ij, and M_ji is stored too.
using SymmetricRows = std::vector<std::map<int, cln::cl_RA>>;
/// Sparse elimination in index order, O(m b²) for a matrix of bandwidth b.
std::optional<NegativeMinor> find_negative_minor(SymmetricRows M);
/// Whether the matrix M of \p scene (its declared entries, on the pairs they
/// involve) is positive semi-definite, decided exactly: find_negative_minor()
/// finds no negative principal minor.
bool positive_semidefinite(const ExactScene& scene);

///@{
/// The explicit instantiations of scaling_of() compiled into the library, one per scalar type.
extern template SUPERBALL_NUMERIC_EXPORT Scaling scaling_of(const Problem<double>&);
extern template SUPERBALL_NUMERIC_EXPORT Scaling scaling_of(const Problem<long double>&);
extern template SUPERBALL_NUMERIC_EXPORT Scaling scaling_of(const Problem<cln::cl_R>&);
extern template SUPERBALL_NUMERIC_EXPORT Scaling scaling_of(const Problem<MpFloat>&);
extern template SUPERBALL_NUMERIC_EXPORT Scaling scaling_of(const Problem<cln::cl_RA>&);
///@}
extern template struct SUPERBALL_NUMERIC_EXPORT Problem<double>;
extern template struct SUPERBALL_NUMERIC_EXPORT Problem<long double>;
extern template struct SUPERBALL_NUMERIC_EXPORT Problem<cln::cl_R>;
extern template struct SUPERBALL_NUMERIC_EXPORT Problem<MpFloat>;
extern template struct SUPERBALL_NUMERIC_EXPORT Problem<cln::cl_RA>;

}  // namespace superball::numeric

SUPERBALL_NUMERIC_API_END
