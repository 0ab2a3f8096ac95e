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
  /// Set the parameter in \p scene to \p value (adds an entry of M if it was absent).
  void set(Scene& scene, const Number& value) const;

 private:
  enum class Kind { Entry, Mass, Velocity, DropHeight, FallSpeed, Gravity } kind_ = Kind::Entry;
  std::string key_;
  Pair first, second;
  int body = 0;
};

}  // namespace superball
