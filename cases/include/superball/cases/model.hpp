#pragma once
/// \file model.hpp
/// The vocabulary of the project (paper §1–§3, generalised from 4 to n bodies):
/// bodies numbered 1 (top) … n (bottom) on a vertical axis, pairs (i<j) with
/// relative velocity D_ij(U) = U_i − U_j, adjacent contacts (i, i+1), the
/// dissipation matrix M indexed by pairs, and evolution cases.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "superball/cases/number.hpp"
#include "superball/cases/export.hpp"
SUPERBALL_CASES_API_BEGIN

namespace superball {

/// A pair of bodies i < j (1-based), written "i-j".
struct Pair {
  /// The upper body (1-based), i < j.
  int i = 1;
  /// The lower body (1-based).
  int j = 2;

  /// Parse "i-j" with 1 <= i < j; throws std::invalid_argument("Pair::parse(): ...").
  static Pair parse(std::string_view text);
  std::string name() const;  ///< "i-j"
  /// True for a contact: the adjacent pair (i, i+1).
  bool adjacent() const { return j == i + 1; }
  ///@{
  /// Equality of both bodies (and its negation).
  friend bool operator==(const Pair& a, const Pair& b) { return a.i == b.i && a.j == b.j; }
  friend bool operator!=(const Pair& a, const Pair& b) { return !(a == b); }
  ///@}
  /// Lexicographic order (i, then j): the paper's order 1-2, 1-3, 1-4, 2-3, …
  friend bool operator<(const Pair& a, const Pair& b) { return a.i != b.i ? a.i < b.i : a.j < b.j; }
};

/// One entry of the symmetric dissipation matrix M (paper §3): the diagonal
/// coefficient K_p when first == second, else the coupling between two pairs
/// (the paper's α's for n = 4).  Stored once, with first < second.
struct MatrixEntry {
  /// The row's pair (first < second, or first == second for a diagonal entry).
  Pair first;
  /// The column's pair.
  Pair second;
  /// The coefficient, exact as written in the scene.
  Number value;
  /// True for a diagonal coefficient K_p (first == second).
  bool diagonal() const { return first == second; }
};

/// A set of adjacent contacts that stay closed after the collision: an
/// evolution case (paper §4).  Contact c (0-based) is the pair (c+1, c+2).
class ContactSet {
 public:
  /// A set of no contacts (for no bodies); assign one of the others.
  ContactSet() = default;
  /// The set of no closed contact for \p bodies bodies (bodies − 1 contacts).
  explicit ContactSet(int bodies)
      : contacts_(bodies > 1 ? bodies - 1 : 0), more_(contacts_ > kWord ? static_cast<std::size_t>((contacts_ - 1) / kWord) : 0, 0) {}
  /// Parse "2-3,3-4" (or "" / "none" for no closed contact) for n bodies;
  /// throws std::invalid_argument("ContactSet::parse(): ...").
  static ContactSet parse(std::string_view text, int bodies);
  /// The set whose bit c is bit c of \p mask (n <= 64).
  static ContactSet from_mask(std::uint64_t mask, int bodies);

  /// The number of bodies n.
  int bodies() const { return contacts_ + 1; }
  /// The number of adjacent contacts, n − 1.
  int contacts() const { return contacts_; }
  /// Whether contact \p c (0-based; the pair (c+1, c+2)) stays closed.
  bool closed(int c) const { return (word(c) >> (c % kWord)) & 1u; }
  /// Close (\p value true) or open contact \p c (0-based).
  void set_closed(int c, bool value) {
    const std::uint64_t bit = std::uint64_t{1} << (c % kWord);
    std::uint64_t& w = c < kWord ? first_ : more_[static_cast<std::size_t>(c / kWord - 1)];
    w = value ? w | bit : w & ~bit;
  }
  std::vector<std::string> closed_names() const;  ///< {"2-3", "3-4"}
  std::string to_string() const;                  ///< "{2-3,3-4}"
  ///@{
  /// Equality of the closed contacts (and its negation); sets for different n differ.
  friend bool operator==(const ContactSet& a, const ContactSet& b) {
    return a.contacts_ == b.contacts_ && a.first_ == b.first_ && a.more_ == b.more_;
  }
  friend bool operator!=(const ContactSet& a, const ContactSet& b) { return !(a == b); }
  ///@}

 private:
  /// Contacts per word of the set.
  static constexpr int kWord = 64;
  /// The word that holds contact \p c.
  std::uint64_t word(int c) const { return c < kWord ? first_ : more_[static_cast<std::size_t>(c / kWord - 1)]; }

  int contacts_ = 0;
  /// Contacts 0 … 63, bit c for contact c: a set of up to 65 bodies is held
  /// without allocation (a map or a sweep makes one per point).
  std::uint64_t first_ = 0;
  /// Contacts 64 onwards, 64 a word, for more than 65 bodies (else empty).
  std::vector<std::uint64_t> more_;
};

/// A body of a scene, top to bottom.
struct Body {
  Number mass;                     ///< > 0 unless infinite
  bool infinite = false;           ///< a fixed obstacle (bottom body only)
  std::optional<Number> velocity;  ///< velocity before the collision, if given
  /// Distance (m) to the body below at release, for a drop ([drop]); absent or 0: touching.
  std::optional<Number> gap;
};

/// The flight after the collision, computed only when a scene asks for it
/// with a [flight] table: each body's free flight under gravity g.
struct Flight {
  /// True when the scene has a [flight] table (even an empty one).
  bool requested = false;
  std::optional<Number> duration;  ///< seconds to draw; default: until the highest apex is passed twice over
};

/// The whole drop, computed only when a scene asks for it with a [drop]
/// table: the bodies released on a vertical line under gravity, every
/// collision and flight followed in time order (numeric/drop.hpp).
struct Drop {
  /// True when the scene has a [drop] table (even an empty one).
  bool requested = false;
  /// `until`: seconds simulated; nullopt is "apex" (the default), the top
  /// body's first apex after its last collision.
  std::optional<Number> until;
  /// `max_events`: the most collisions followed before the drop stops (default 10,000).
  long long max_events = 10000;
  /// `distant`: every pair declared in M takes part in every collision (default false: the touching cluster).
  bool distant = false;
};

/// A scene: the bodies and only the effects that are in play.
struct Scene {
  /// The scene's title (its `title` key), for reports.
  std::string title;
  std::string origin;  ///< the file it came from (for messages), or a label
  /// The bodies, top (body 1) to bottom (body n).
  std::vector<Body> bodies;
  std::optional<Number> drop_height;  ///< h: falling bodies move at -sqrt(2 g h)
  std::optional<Number> fall_speed;   ///< a directly: falling bodies move at -a
  /// Gravity g (m/s²; the `g` key, default 9.81), for the drop height and the flight.
  Number g = Number::parse("9.81");
  std::vector<MatrixEntry> entries;   ///< declared entries of M only
  /// The flight after the collision, when asked for ([flight]).
  Flight flight;
  /// The whole drop, when asked for ([drop]).
  Drop drop;

  /// The number of bodies n.
  int size() const { return static_cast<int>(bodies.size()); }
  /// The declared entry for (p, q) in either order, if any.
  const MatrixEntry* find(const Pair& p, const Pair& q) const;
};

}  // namespace superball

SUPERBALL_CASES_API_END
