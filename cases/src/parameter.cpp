#include "superball/cases/parameter.hpp"

#include <algorithm>
#include <stdexcept>

#include "superball/cases/scene_file.hpp"
#include "superball/cases/vocabulary.hpp"

namespace superball {
namespace {

[[noreturn]] void bad(const std::string& key, const std::string& why) {
  throw std::invalid_argument("Parameter::parse(): " + printable("'" + key + "': " + why));
}

Pair pair_of(const std::string& key, const std::string& text, int n) {
  Pair p;
  try {
    p = Pair::parse(text);
  } catch (const std::invalid_argument&) {
    bad(key, "'" + text + "' is not a pair i-j");
  }
  if (p.j > n) bad(key, "pair " + p.name() + " is outside bodies 1.." + std::to_string(n));
  return p;
}

/// A body or alpha index: decimal digits only (leading zeros allowed, so
/// `mass.01` is `mass.1`), at most 9 of them; 0 for anything else.
int index_of(const std::string& text) {
  if (text.empty() || text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos) return 0;
  return std::stoi(text);
}

int body_of(const std::string& key, const std::string& text, int n) {
  const int b = index_of(text);
  if (b < 1 || b > n) bad(key, "body must be 1.." + std::to_string(n));
  return b;
}

}  // namespace

Parameter Parameter::parse(const std::string& key, const Scene& scene) {
  Parameter p;
  p.spelling_ = key;
  const int n = scene.size();
  const auto dot = key.find('.');
  const std::string head = key.substr(0, dot), tail = dot == std::string::npos ? "" : key.substr(dot + 1);
  if (head == "K") {
    p.kind_ = Kind::Entry;
    p.first = p.second = pair_of(key, tail, n);
  } else if (head == "alpha") {
    const Vocabulary& v = Vocabulary::paper();
    if (n != v.bodies()) bad(key, "the paper's alpha_k name couplings of 4 bodies; use coupling.i-j/k-l");
    const int k = index_of(tail);
    if (k < 1 || k > static_cast<int>(v.alphas().size())) bad(key, "alpha must be 1.." + std::to_string(v.alphas().size()));
    p.kind_ = Kind::Entry;
    p.first = v.alpha(k).first;
    p.second = v.alpha(k).second;
    if (p.second < p.first) std::swap(p.first, p.second);
  } else if (head == "coupling") {
    const auto slash = tail.find('/');
    if (slash == std::string::npos) bad(key, "write coupling.i-j/k-l");
    p.kind_ = Kind::Entry;
    p.first = pair_of(key, tail.substr(0, slash), n);
    p.second = pair_of(key, tail.substr(slash + 1), n);
    if (p.first == p.second) bad(key, "a coupling joins two different pairs (use K.i-j)");
    if (p.second < p.first) std::swap(p.first, p.second);
  } else if (head == "mass" || head == "velocity") {
    p.kind_ = head == "mass" ? Kind::Mass : Kind::Velocity;
    p.body = body_of(key, tail, n);
    if (p.kind_ == Kind::Mass && scene.bodies[static_cast<std::size_t>(p.body - 1)].infinite)
      bad(key, "body " + std::to_string(p.body) + " is a fixed obstacle (infinite mass)");
  } else if (head == "gap") {
    if (!scene.drop.requested) bad(key, "a gap is a release position of a drop; the scene has no [drop] table");
    p.kind_ = Kind::Gap;
    p.body = index_of(tail);
    // Body n − 1's distance to the bottom body is drop_height; the bottom body has none below it.
    if (p.body < 1 || p.body > n - 2)
      bad(key, (n > 2 ? "body must be 1.." + std::to_string(n - 2) : std::string("no gap to vary with 2 bodies")) +
                   " (gap.i is body i's distance to the body below it; body " + std::to_string(n - 1) + "'s is drop_height)");
  } else if (key == "drop_height" || key == "fall_speed" || key == "g") {
    p.kind_ = key == "g" ? Kind::Gravity : key == "drop_height" ? Kind::DropHeight : Kind::FallSpeed;
    if (p.kind_ == Kind::DropHeight && scene.fall_speed) bad(key, "the scene gives fall_speed, not drop_height");
    if (p.kind_ == Kind::FallSpeed && scene.drop_height) bad(key, "the scene gives drop_height, not fall_speed");
  } else {
    bad(key, "unknown parameter (expected K.i-j, alpha.k, coupling.i-j/k-l, mass.i, velocity.i, gap.i (a drop), drop_height, fall_speed or g)");
  }
  p.key_ = p.canonical(n);
  return p;
}

std::string Parameter::canonical(int bodies) const {
  switch (kind_) {
    case Kind::Entry: {
      if (first == second) return "K." + first.name();
      const Vocabulary& v = Vocabulary::paper();
      if (bodies == v.bodies())
        if (const auto k = v.alpha_index(first, second)) return "alpha." + std::to_string(*k);
      return "coupling." + first.name() + "/" + second.name();
    }
    case Kind::Mass: return "mass." + std::to_string(body);
    case Kind::Velocity: return "velocity." + std::to_string(body);
    case Kind::Gap: return "gap." + std::to_string(body);
    case Kind::DropHeight: return "drop_height";
    case Kind::FallSpeed: return "fall_speed";
    case Kind::Gravity: return "g";
  }
  return "";
}

bool operator==(const Parameter& a, const Parameter& b) {
  return a.kind_ == b.kind_ && a.first == b.first && a.second == b.second && a.body == b.body;
}

void Parameter::assign(Scene& s, const Number& value) const {
  switch (kind_) {
    case Kind::Entry: {
      auto same = [&](const MatrixEntry& e) { return (e.first == first && e.second == second) || (e.first == second && e.second == first); };
      const auto e = std::find_if(s.entries.begin(), s.entries.end(), same);
      if (e != s.entries.end())
        e->value = value;
      else
        s.entries.push_back({first, second, value});
      break;
    }
    case Kind::Mass: s.bodies[static_cast<std::size_t>(body - 1)].mass = value; break;
    case Kind::Velocity: s.bodies[static_cast<std::size_t>(body - 1)].velocity = value; break;
    case Kind::Gap: s.bodies[static_cast<std::size_t>(body - 1)].gap = value; break;
    case Kind::DropHeight: s.drop_height = value; break;
    case Kind::FallSpeed: s.fall_speed = value; break;
    case Kind::Gravity: s.g = value; break;
  }
}

void Parameter::set(Scene& scene, const Number& value) const {
  Scene s = scene;
  assign(s, value);
  // The loader's own checks, on the scene as a file would give it.
  try {
    (void)parse_scene(write_scene(s), s.origin);
  } catch (const InputError& e) {
    // "ORIGIN:LINE:COL: field: why": the place is in the rewritten text, not in the user's file.
    const std::string what = e.what();
    const auto at = what.find(": ", std::min(what.size(), s.origin.size()));
    throw InputError(s.origin + ": " + key_ + " = " + value.text + ": " + (at == std::string::npos ? what : what.substr(at + 2)));
  }
  scene = std::move(s);
}

}  // namespace superball
