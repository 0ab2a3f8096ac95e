#pragma once
/// \file parameter.hpp
/// Names of the scene parameters a sweep or a verification can vary.

#include <string>

#include "superball/cases/model.hpp"
#include "superball/cases/export.hpp"
SUPERBALL_CASES_API_BEGIN

namespace superball {

/// A scalar parameter of a scene, named as on the command line:
/// `K.3-4` (diagonal of M), `alpha.2` (the paper's α₂, n = 4),
/// `coupling.1-2/1-4` (off-diagonal entry of M), `mass.1`, `velocity.4`,
/// `drop_height`, `fall_speed`, `g`, and for a scene with a [drop] table
/// `gap.1` (body 1's gap to the body below it at release, m).
///
/// One entry of the scene has several spellings, all parsed into the same
/// Parameter: indices may have leading zeros (`K.03-4` is `K.3-4`,
/// `mass.01` is `mass.1`), a coupling's two pairs come in either order
/// (`coupling.1-4/1-2` is `coupling.1-2/1-4`), and for 4 bodies the paper's
/// `alpha.k` is the coupling it names (`alpha.2` is `coupling.1-2/1-4`).
/// Parameters compare equal when they name the same entry; key() is the one
/// canonical spelling, spelling() the one given.
class Parameter {
 public:
  /// Parse \p key for \p scene; throws std::invalid_argument("Parameter::parse(): ...").
  static Parameter parse(const std::string& key, const Scene& scene);
  /// The canonical spelling, used in every output: `K.i-j` and
  /// `coupling.i-j/k-l` with indices in decimal without leading zeros and
  /// the pairs in increasing order, `alpha.k` for a coupling the paper names
  /// (4 bodies), `mass.i`, `velocity.i`, `gap.i`, `drop_height`, `fall_speed`, `g`.
  const std::string& key() const { return key_; }
  /// The spelling parse() was given, for messages that quote the user.
  const std::string& spelling() const { return spelling_; }
  /// Whether \p a and \p b name the same entry of a scene (whatever their spellings).
  friend bool operator==(const Parameter& a, const Parameter& b);
  /// Whether \p a and \p b name different entries.
  friend bool operator!=(const Parameter& a, const Parameter& b) { return !(a == b); }
  /// Set the parameter in \p scene to \p value (adds an entry of M if it was
  /// absent), through the scene loader's own checks: the scene with the new
  /// value is written as a scene file and read back (write_scene(),
  /// parse_scene()), so that a value a file could not hold (g <= 0, a
  /// negative drop_height or fall_speed, a mass <= 0, …) is refused as the
  /// file would be.  Throws InputError("ORIGIN: KEY = VALUE: field: what is
  /// wrong") and leaves \p scene unchanged.  The numeric entry checks (M
  /// positive semi-definite, no contact opening before the collision) are
  /// the numeric backend's (ExactScene::from()).
  void set(Scene& scene, const Number& value) const;
  /// set() without the checks, for the many values of a sweep (a scene file
  /// written and read back per value would cost far more than the solve):
  /// only for a value between two values that passed every check (the
  /// checks admit an interval along one parameter; numeric::check_range()).
  void assign(Scene& scene, const Number& value) const;

 private:
  enum class Kind { Entry, Mass, Velocity, Gap, DropHeight, FallSpeed, Gravity } kind_ = Kind::Entry;
  std::string key_, spelling_;
  Pair first, second;  ///< Entry: first <= second
  int body = 0;
  /// The canonical key for a scene of \p bodies bodies.
  std::string canonical(int bodies) const;
};
/// Declared here too, not only as a friend, so that the shared library exports it.
bool operator==(const Parameter& a, const Parameter& b);

}  // namespace superball

SUPERBALL_CASES_API_END
