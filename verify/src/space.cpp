#include "superball/verify/space.hpp"

#include <cln/rational_io.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

#include "superball/cases/error.hpp"
#include "superball/numeric/scalar.hpp"

namespace superball::verify {
namespace detail {

cln::cl_RA to_rational(const GiNaC::numeric& x) { return cln::rational(cln::the<cln::cl_RA>(x.to_cl_N())); }

}  // namespace detail

cln::cl_RA deep_copy(const cln::cl_RA& x) { return numeric::parse_rational(to_string(x)); }

Point deep_copy(const Point& x) {
  Point out;
  out.reserve(x.size());
  for (const cln::cl_RA& v : x) out.push_back(deep_copy(v));
  return out;
}

std::string to_string(const cln::cl_RA& x) {
  std::ostringstream os;
  cln::fprint(os, x);
  return os.str();
}

// ---------------------------------------------------------------------------- Polynomial

Polynomial::Polynomial(const GiNaC::ex& p, const symbolic::Symbols& symbols) {
  try {
    for (const symbolic::Monomial& m : symbols.monomials(p)) {
      Term t;
      t.coefficient = detail::to_rational(m.coefficient);
      t.approx = cln::double_approx(t.coefficient);
      t.powers = m.powers;
      terms_.push_back(std::move(t));
    }
    // A fixed order of the terms and factors (GiNaC's order of a sum or a
    // product is not reproducible between runs), so the double evaluation
    // rounds the same every time.
    for (Term& t : terms_) std::sort(t.powers.begin(), t.powers.end());
    std::sort(terms_.begin(), terms_.end(), [](const Term& a, const Term& b) { return a.powers < b.powers; });
    prepare();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("Polynomial::Polynomial(): " + without_function_prefix(e.what()));
  }
}

cln::cl_RA Polynomial::operator()(const Point& x) const {
  cln::cl_RA sum = 0;
  for (const Term& t : terms_) {
    cln::cl_RA v = t.coefficient;
    for (const auto& [k, e] : t.powers) v = v * cln::expt(x[static_cast<std::size_t>(k)], e);
    sum = sum + v;
  }
  return sum;
}

void Polynomial::prepare() {
  used_.clear();
  degree_ = 0;
  filter_ = true;
  for (const Term& t : terms_) {
    int e = 0;
    for (const auto& [k, power] : t.powers) {
      used_.push_back(k);
      e += power;
      filter_ = filter_ && power >= 0 && k >= 0;
    }
    degree_ = std::max(degree_, e);
    filter_ = filter_ && std::isnormal(t.approx);
  }
  std::sort(used_.begin(), used_.end());
  used_.erase(std::unique(used_.begin(), used_.end()), used_.end());
}

int Polynomial::sign(const Point& x) const {
  if (terms_.empty()) return 0;
  constexpr std::size_t kMost = 64;  // coordinates held on the stack
  constexpr double u = 0x1p-53, low = 0x1p-1000, high = 0x1p1000;
  // A product outside [low, high] (but not 0) may have lost its relative accuracy: the exact value decides.
  const auto in_range = [&](double v) { return v == 0 || (std::fabs(v) >= low && std::fabs(v) <= high); };
  bool decided = filter_ && !used_.empty() && static_cast<std::size_t>(used_.back()) < std::min(x.size(), kMost);
  double xd[kMost];
  for (std::size_t j = 0; decided && j < used_.size(); ++j) {
    const cln::cl_RA& v = x[static_cast<std::size_t>(used_[j])];
    const double d = cln::double_approx(v);  // a value that is not 0 but rounds to 0 or out of range: the exact path
    decided = in_range(d) && (d != 0 || cln::zerop(v));
    xd[used_[j]] = d;
  }
  if (decided) {
    double sum = 0, magnitude = 0;
    for (const Term& t : terms_) {
      double v = t.approx;
      for (const auto& [k, e] : t.powers)
        for (int r = 0; r < e && decided; ++r) v *= xd[k], decided = in_range(v);
      sum += v;
      magnitude += std::fabs(v);
    }
    const double terms = static_cast<double>(terms_.size()), products = 2.0 + 3.0 * degree_;
    const auto gamma = [&](double k) { return k * u / (1 - k * u); };
    const double bound = 2 * (gamma(terms) + 2 * gamma(products)) * magnitude;
    if (decided && std::isfinite(sum) && std::isfinite(bound) && std::fabs(sum) > bound) return sum > 0 ? 1 : -1;
  }
  const cln::cl_RA exact = (*this)(x);
  return cln::zerop(exact) ? 0 : cln::minusp(exact) ? -1 : 1;
}

double Polynomial::operator()(const std::vector<double>& x) const {
  double sum = 0;
  for (const Term& t : terms_) {
    double v = t.approx;
    for (const auto& [k, e] : t.powers) v *= std::pow(x[static_cast<std::size_t>(k)], e);
    sum += v;
  }
  return sum;
}

Polynomial Polynomial::clone() const {
  Polynomial out;
  out.terms_.reserve(terms_.size());
  for (const Term& t : terms_) out.terms_.push_back(Term{deep_copy(t.coefficient), t.approx, t.powers});
  out.prepare();
  return out;
}

// ---------------------------------------------------------------------------- CompiledCondition

CompiledCondition::CompiledCondition(const symbolic::Condition& condition, const symbolic::ConditionForm& form,
                                     const symbolic::Symbols& symbols)
    : kind(condition.kind),
      about(condition.about),
      strict(condition.relation == symbolic::Relation::Greater),
      numerator(form.numerator, symbols) {
  if (!form.sign_proved()) denominator = Polynomial(form.denominator, symbols);
}

bool CompiledCondition::holds(const Point& x) const {
  int sign = numerator.sign(x);
  if (!denominator.is_zero()) {
    const int d = denominator.sign(x);
    if (d == 0) return false;
    sign *= d;
  }
  return strict ? sign > 0 : sign >= 0;
}

double CompiledCondition::value(const std::vector<double>& x) const {
  const double n = numerator(x);
  if (denominator.is_zero()) return n;
  const double d = denominator(x);
  return d == 0 ? std::nan("") : n / d;
}

CompiledCondition CompiledCondition::clone() const {
  CompiledCondition out;
  out.kind = kind;
  out.about = about;
  out.strict = strict;
  out.numerator = numerator.clone();
  out.denominator = denominator.clone();
  return out;
}

// ---------------------------------------------------------------------------- ParameterSpace

ParameterSpace::ParameterSpace(const symbolic::Deriver& deriver) {
  const symbolic::Symbols& sy = deriver.symbols();
  bodies_ = sy.bodies();
  fixed_bottom_ = sy.obstacle() == symbolic::Obstacle::Infinite;
  std::map<std::string, int> diagonal;
  for (const symbolic::SymbolInfo& s : sy.all()) {
    Coordinate c;
    c.kind = s.kind;
    c.ascii = s.ascii;
    c.text = s.text;
    c.body = s.body;
    c.first = s.first;
    c.second = s.second;
    const GiNaC::numeric k = deriver.scaling().order(sy, s.symbol);
    if (!k.is_integer())
      throw std::invalid_argument("ParameterSpace::ParameterSpace(): sampling needs integer orders in epsilon (" + s.ascii + ")");
    if (GiNaC::abs(k) > max_sampling_order) {
      std::ostringstream order;
      order << k;
      throw std::invalid_argument("ParameterSpace::ParameterSpace(): sampling needs orders in epsilon from " +
                                  std::to_string(-max_sampling_order) + " to " + std::to_string(max_sampling_order) + " (" + s.ascii +
                                  " has order " + order.str() + ")");
    }
    c.order = k.to_int();
    const int at = static_cast<int>(coordinates_.size());
    if (s.kind == symbolic::SymbolKind::Diagonal) diagonal[s.first.name()] = at;
    if (s.kind == symbolic::SymbolKind::FallSpeed) fall_speed_ = at;
    coordinates_.push_back(std::move(c));
  }
  for (Coordinate& c : coordinates_) {
    if (c.kind != symbolic::SymbolKind::Coupling) continue;
    if (const auto it = diagonal.find(c.first.name()); it != diagonal.end()) c.first_diagonal = it->second;
    if (const auto it = diagonal.find(c.second.name()); it != diagonal.end()) c.second_diagonal = it->second;
  }
  for (const symbolic::Condition& m : deriver.psd()) psd_.emplace_back(m.exact.numerator, sy);
}

int ParameterSpace::index(const std::string& ascii) const {
  for (std::size_t k = 0; k < coordinates_.size(); ++k)
    if (coordinates_[k].ascii == ascii) return static_cast<int>(k);
  std::string list;
  for (const Coordinate& c : coordinates_) list += (list.empty() ? "" : ", ") + c.ascii;
  throw std::invalid_argument("ParameterSpace::index(): no parameter '" + ascii + "' in this pattern (it has " + list + ")");
}

bool ParameterSpace::admissible(const Point& x) const {
  if (x.size() != coordinates_.size()) return false;
  for (std::size_t k = 0; k < x.size(); ++k)
    if (coordinates_[k].kind != symbolic::SymbolKind::Coupling && !cln::plusp(x[k])) return false;
  for (const Polynomial& m : psd_)
    if (m.sign(x) < 0) return false;
  return true;
}

numeric::Problem<cln::cl_RA> ParameterSpace::problem(const Point& x) const {
  if (x.size() != coordinates_.size())
    throw std::invalid_argument("ParameterSpace::problem(): the point has " + std::to_string(x.size()) + " values, the space " +
                                std::to_string(coordinates_.size()));
  numeric::Problem<cln::cl_RA> p;
  p.n = bodies_;
  p.fixed_bottom = fixed_bottom_;
  p.mass.assign(static_cast<std::size_t>(bodies_), cln::cl_RA(0));
  p.unit = 1;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const Coordinate& c = coordinates_[k];
    switch (c.kind) {
      case symbolic::SymbolKind::Mass: p.mass[static_cast<std::size_t>(c.body - 1)] = x[k]; break;
      case symbolic::SymbolKind::Diagonal:
      case symbolic::SymbolKind::Coupling:
        p.entries.push_back({c.first.i - 1, c.first.j - 1, c.second.i - 1, c.second.j - 1, x[k]});
        break;
      case symbolic::SymbolKind::FallSpeed: break;
    }
  }
  const cln::cl_RA& a = x[static_cast<std::size_t>(fall_speed_)];
  for (int i = 0; i < bodies_; ++i) p.u.push_back(i + 1 < bodies_ ? cln::cl_RA(-a) : cln::cl_RA(0));
  return p;
}

Scene ParameterSpace::scene(const Point& x, const std::string& title) const {
  const numeric::Problem<cln::cl_RA> p = problem(x);
  auto number = [](const cln::cl_RA& v) { return Number::parse(to_string(v)); };
  Scene s;
  s.title = title;
  s.origin = title;
  s.fall_speed = number(x[static_cast<std::size_t>(fall_speed_)]);
  for (int i = 0; i < bodies_; ++i) {
    Body b;
    if (i + 1 == bodies_) {
      b.velocity = Number::integer(0);
      b.infinite = fixed_bottom_;
    }
    if (!b.infinite) b.mass = number(p.mass[static_cast<std::size_t>(i)]);
    s.bodies.push_back(b);
  }
  for (const auto& e : p.entries) s.entries.push_back({Pair{e.i + 1, e.j + 1}, Pair{e.k + 1, e.l + 1}, number(e.value)});
  return s;
}

std::vector<std::pair<std::string, cln::cl_RA>> ParameterSpace::named(const Point& x) const {
  std::vector<std::pair<std::string, cln::cl_RA>> out;
  for (std::size_t k = 0; k < coordinates_.size() && k < x.size(); ++k) out.emplace_back(coordinates_[k].ascii, x[k]);
  return out;
}

ParameterSpace ParameterSpace::clone() const {
  ParameterSpace out;
  out.coordinates_ = coordinates_;
  for (const Polynomial& m : psd_) out.psd_.push_back(m.clone());
  out.bodies_ = bodies_;
  out.fall_speed_ = fall_speed_;
  out.fixed_bottom_ = fixed_bottom_;
  return out;
}

// ---------------------------------------------------------------------------- RegimeSampler

RegimeSampler::RegimeSampler(const ParameterSpace& space, const cln::cl_RA& epsilon, std::uint64_t seed)
    : space_(space), epsilon_(deep_copy(epsilon)), rng_(seed) {
  if (!(epsilon_ > 0) || !(epsilon_ < 1)) throw std::invalid_argument("RegimeSampler::RegimeSampler(): epsilon must be in (0, 1)");
  // A point's values are O(1)·eps^order; they must stay numbers a scene
  // holds (decimal exponents within ±max_decimal_exponent), since a point
  // that disagrees is written as one.
  int largest = 0;
  for (const Coordinate& c : space_.coordinates()) largest = std::max(largest, std::abs(c.order));
  const cln::cl_RA limit = cln::expt(cln::cl_RA(10), -(max_decimal_exponent - 2));
  if (largest > 0 && cln::expt(epsilon_, largest) < limit)
    throw std::invalid_argument("RegimeSampler::RegimeSampler(): eps = " + to_string(epsilon_) + " to the order " + std::to_string(largest) +
                                " of the scaling is below 1e-" + std::to_string(max_decimal_exponent - 2) +
                                ": the points would hold numbers no scene holds (use a larger eps or smaller orders)");
}

std::optional<Point> RegimeSampler::draw() {
  for (int attempt = 0; attempt < 1000; ++attempt) {
    Point x = candidate();
    if (space_.admissible(x)) return x;
  }
  return std::nullopt;
}

Point RegimeSampler::candidate() {
  auto tenths = [&](int lo, int hi) { return cln::cl_RA(std::uniform_int_distribution<int>(lo, hi)(rng_)) / 10; };
  const auto& coords = space_.coordinates();
  Point x(coords.size());
  for (std::size_t k = 0; k < coords.size(); ++k) {
    const Coordinate& c = coords[k];
    const cln::cl_RA scale = cln::expt(epsilon_, c.order);
    switch (c.kind) {
      case symbolic::SymbolKind::Mass: x[k] = tenths(1, 300) * scale; break;
      case symbolic::SymbolKind::Diagonal: x[k] = tenths(1, 200) * scale; break;
      case symbolic::SymbolKind::Coupling: {
        // |c| <= sqrt(K_p K_q) for the 2×2 minor, and O(1): at most 20 before scaling.
        double bound = 20;
        if (c.first_diagonal >= 0 && c.second_diagonal >= 0)
          bound = std::min(bound, std::sqrt(cln::double_approx(x[static_cast<std::size_t>(c.first_diagonal)] *
                                                               x[static_cast<std::size_t>(c.second_diagonal)])) /
                                      cln::double_approx(scale));
        const cln::cl_RA b = cln::cl_RA(static_cast<long>(std::floor(bound * 10))) / 10;
        x[k] = scale * b * cln::cl_RA(std::uniform_int_distribution<int>(-20, 20)(rng_)) / 20;
        break;
      }
      case symbolic::SymbolKind::FallSpeed: x[k] = tenths(10, 50); break;
    }
  }
  return x;
}

// ---------------------------------------------------------------------------- truth

bool condition_truth(symbolic::ConditionKind kind, const std::string& about, const numeric::Problem<cln::cl_RA>& problem,
                     const numeric::Solution<cln::cl_RA>& forced, std::string* quantity) {
  std::string q;
  bool truth = false;
  const auto& u = forced.velocities_after;
  switch (kind) {
    case symbolic::ConditionKind::Superball: {
      const cln::cl_RA a = -problem.u.front();
      q = "U1 - a = " + to_string(u[0] - a);
      truth = u[0] > a;
      break;
    }
    case symbolic::ConditionKind::Evolution:
    case symbolic::ConditionKind::Contact: {
      const Pair p = Pair::parse(about);
      const auto i = static_cast<std::size_t>(p.i - 1), j = static_cast<std::size_t>(p.j - 1);
      if (kind == symbolic::ConditionKind::Evolution) {
        q = "U" + std::to_string(p.i) + " - U" + std::to_string(p.j) + " = " + to_string(u[i] - u[j]);
        truth = u[i] > u[j];
      } else {
        q = "R" + std::to_string(p.i) + "_" + std::to_string(p.j) + " = " + to_string(forced.reactions[i]);
        truth = forced.reactions[i] <= 0;
      }
      break;
    }
    case symbolic::ConditionKind::Psd:
      throw std::invalid_argument("condition_truth(): a PSD condition is not a property of the solution");
  }
  if (quantity) *quantity = q;
  return truth;
}

}  // namespace superball::verify
