#pragma once
/// \file parameter.hpp
/// Names of the scene parameters a sweep or a verification can vary.

#include <string>

#include "superball/cases/model.hpp"

namespace superball {

/// A scalar parameter of a scene, named as on the command line:
/// `K.3-4` (diagonal of M), `alpha.2` (the paper's α₂, n = 4),
/// `coupling.1-2/1-4` (off-diagonal entry of M), `mass.1`, `velocity.4`,
/// `drop_height`, `fall_speed`, `g`.
class Parameter {
 public:
  /// Parse \p key for \p scene; throws std::invalid_argument("Parameter::parse(): ...").
  static Parameter parse(const std::string& key, const Scene& scene);
  const std::string& key() const { return key_; }
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
  enum class Kind { Entry, Mass, Velocity, DropHeight, FallSpeed, Gravity } kind_ = Kind::Entry;
  std::string key_;
  Pair first, second;
  int body = 0;
};

}  // namespace superball
