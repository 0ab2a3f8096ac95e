#include "superball/numeric/drop.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include <cln/integer.h>

#include "superball/cases/error.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/numeric/collision.hpp"
#include "superball/numeric/mpfloat.hpp"
#include "superball/numeric/problem.hpp"

namespace superball::numeric {
namespace {

/// The exact rational value of a double or long double.
template <class S>
cln::cl_RA to_exact(S x) {
  if (x == S(0) || !std::isfinite(x)) return 0;  // (a datum out of range fails the solve in S first)
  int e = 0;
  const S f = std::frexp(x, &e);  // |f| in [1/2, 1)
  const unsigned long long m = static_cast<unsigned long long>(std::ldexp(std::fabs(f), 64 - 1) * 2);  // all 64 (or 53) bits
  const cln::cl_RA r = cln::cl_I(m) * cln::expt(cln::cl_RA(2), e - 64);
  return x < S(0) ? cln::cl_RA(-r) : r;
}

/// The exact rational value of an MPFR float (numeric::rational()).
cln::cl_RA to_exact(const MpFloat& x) { return rational(x); }

/// The collision of \p p solved in S, and again in exact rationals from the
/// same (rounded) data when S's solve fails its residual check (stiff
/// contacts, K/m of 10⁶ and more in double; of 10¹⁰ and more in digits:30,
/// whose residual grows as K/m times the unit roundoff).
template <class S>
Solution<S> solve_collision(const Problem<S>& p) {
  Solution<S> sol = solve(p);
  if constexpr (ScalarTraits<S>::exact) {
    return sol;
  } else {
    if (sol.status == Status::Success) return sol;
    Problem<cln::cl_RA> q;
    q.n = p.n;
    q.fixed_bottom = p.fixed_bottom;
    q.constrained = p.constrained;
    for (int i = 0; i < p.n; ++i) q.mass.push_back(p.fixed_bottom && i == p.n - 1 ? cln::cl_RA(0) : to_exact(p.mass[i]));  // the obstacle's is unused
    for (const S& u : p.u) q.u.push_back(to_exact(u));
    for (const Entry<S>& e : p.entries) q.entries.push_back({e.i, e.j, e.k, e.l, to_exact(e.value)});
    const Solution<cln::cl_RA> exact = solve(q);
    if (exact.status != Status::Success) return sol;
    sol.status = Status::Success;
    sol.closed = exact.closed;
    sol.velocities_after.assign(exact.velocities_after.size(), S(0));
    for (std::size_t i = 0; i < exact.velocities_after.size(); ++i) sol.velocities_after[i] = ScalarTraits<S>::from(exact.velocities_after[i], p.digits);
    return sol;
  }
}

/// Rational bounds low <= √x <= high of a rational x >= 0, within
/// 2^−128 of √(p·q)/q (x = p/q).
std::pair<cln::cl_RA, cln::cl_RA> sqrt_bounds(const cln::cl_RA& x) {
  const cln::cl_I p = cln::numerator(x), q = cln::denominator(x);
  const cln::cl_I r = cln::isqrt(cln::ash(p * q, 256));
  const cln::cl_RA unit = cln::cl_RA(1) / (q * cln::ash(1, 128));
  return {r * unit, (r + 1) * unit};
}

/// Whether \p a and \p b have the same events (contacts, bodies, case and
/// contacts that stay closed, in order) and end the same way.
bool same_sequence(const DropResult& a, const DropResult& b) {
  if (a.events.size() != b.events.size() || a.end != b.end) return false;
  for (std::size_t k = 0; k < a.events.size(); ++k) {
    const DropEvent &x = a.events[k], &y = b.events[k];
    if (x.contacts != y.contacts || x.first_body != y.first_body || x.last_body != y.last_body || x.case_name != y.case_name ||
        x.closed != y.closed)
      return false;
  }
  return true;
}

/// The state of every body between events, in S, and the run's record.
///
/// In exact rationals (S = cln::cl_RA) a drop onto a fixed obstacle with
/// every body released at rest runs in units that keep it rational: speeds
/// in a = √(2·g·h) (h = drop_height, the lowest body's landing speed), times
/// in 1/a, lengths in m, so that gravity is g/a² = 1/(2h) and the first
/// impact comes at 2h.  A flight between free bodies closes a gap at a
/// rational time; one over the obstacle (or bodies at rest on it) at the
/// root of a quadratic, rational when its discriminant is a square.  When the
/// next event's time is not rational the run ends ("inexact"): exact
/// arithmetic goes as far as it can.
template <class S>
class DropRun {
  using T = ScalarTraits<S>;

 public:
  DropRun(const Scene& scene, const ExactScene& exact, const std::string& precision, int digits)
      : scene_(scene), digits_(digits), full_(Problem<S>::from(exact, digits)), n_(full_.n), fixed_(full_.fixed_bottom), distant_(scene.drop.distant) {
    g_ = T::from(parse_rational(scene.g.fraction()), digits_);
    u_ = T::unit_roundoff(digits_);
    z_.assign(n_, S(0));
    v_.assign(n_, S(0));
    gap_.assign(n_ > 0 ? n_ - 1 : 0, S(0));
    supported_.assign(n_, false);
    if (fixed_) supported_[n_ - 1] = true;
    m_group_.resize(static_cast<std::size_t>(n_));
    for (int i = 0; i < n_; ++i) m_group_[i] = i;
    const auto root = [this](int i) {
      while (m_group_[i] != i) i = m_group_[i];
      return i;
    };
    for (const Entry<S>& e : full_.entries)
      if (e.value != S(0))
        for (int b : {e.j, e.k, e.l}) m_group_[root(b)] = root(e.i);
    // Heights from the bottom: the obstacle at 0, the lowest free body at drop_height, each other one gap above.
    for (int i = n_ - 2; i >= 0; --i) {
      const auto& b = scene.bodies[static_cast<std::size_t>(i)];
      const Number* gap = i == n_ - 2 ? (scene.drop_height ? &*scene.drop_height : nullptr) : (b.gap ? &*b.gap : nullptr);
      gap_[i] = gap ? T::from(parse_rational(gap->fraction()), digits_) : S(0);
      z_[i] = z_[i + 1] + gap_[i];
    }
    for (int i = 0; i < n_; ++i) {
      const auto& b = scene.bodies[static_cast<std::size_t>(i)];
      if (!obstacle(i) && b.velocity) v_[i] = T::from(parse_rational(b.velocity->fraction()), digits_);
    }
    if (scene.drop.until) until_ = T::from(parse_rational(scene.drop.until->fraction()), digits_);
    r_.g = T::to_double(g_);
    const S top = z_[0] - z_[n_ - 1];
    if constexpr (T::exact) {
      if (fixed_ && n_ >= 2 && gap_[n_ - 2] > S(0) && std::all_of(v_.begin(), v_.end(), [](const S& v) { return v == S(0); })) {
        a2_ = 2 * g_ * gap_[n_ - 2];
        a_ = std::sqrt(T::to_double(*a2_));
        g_ = g_ / *a2_;
      }
    } else {
      using std::sqrt;
      time_scale_ = top > S(0) ? S(sqrt(S(2) * top / g_)) : S(1);
    }
    rest_height_ = T::from(to_exact(drop_rest_fraction), digits_) * (top > S(0) ? top : S(1));
    last_t_.assign(n_, S(0));
    last_z_ = z_;
    last_v_ = v_;
    r_.precision = r_.precision_asked = precision;
    r_.distant = distant_;
    r_.fixed_bottom = fixed_;
    for (int i = 0; i < n_; ++i) {
      r_.masses.push_back(obstacle(i) ? std::numeric_limits<double>::infinity() : T::to_double(full_.mass[i]));
      r_.release_heights.push_back(T::to_double(z_[i]));
      r_.release_velocities.push_back(si_speed(v_[i]));
    }
  }

  DropResult run() {
    settle();
    for (;;) {
      const Next next = next_event();
      const S dt = next.delay;
      // The top body's apex, when it comes before anything else can touch it.
      if (!until_ && !supported_[0] && v_[0] > S(0) && (!next.any || S(v_[0] / g_) < dt)) {
        advance(v_[0] / g_);
        end("apex");
        break;
      }
      if (until_ && (!next.any || beyond_until(t_ + dt))) {
        end_at_until();
        break;
      }
      if (!next.any) {
        end(std::all_of(supported_.begin(), supported_.end(), [](bool s) { return s; }) ? "rest" : "no-more-events");
        break;
      }
      if (next.inexact) {
        end("inexact");
        break;
      }
      if (static_cast<long long>(r_.events.size()) >= scene_.drop.max_events) {
        end("max-events");
        break;
      }
      advance(dt);
      ties_ += next.ties;
      near_ties_ += next.near_ties;
      if (!collide(next.closing, T::exact || (next.ties == 0 && next.near_ties == 0))) {
        end("numerical-issue");
        break;
      }
      accumulate();
    }
    return std::move(r_);
  }

 private:
  /// Body \p i is the fixed obstacle (the bottom body of infinite mass): no velocity, momentum or energy of its own.
  bool obstacle(int i) const { return fixed_ && i == n_ - 1; }

  S acceleration(int i) const { return supported_[i] ? S(0) : S(-g_); }

  /// Bodies at rest on the fixed obstacle (directly or on one another) are held by it.
  void settle() {
    for (int i = n_ - 2; i >= 0; --i)
      if (fixed_ && supported_[i + 1] && gap_[i] == S(0) && v_[i] == S(0)) supported_[i] = true;
  }

  /// When a contact closes from now: its time, or in exact arithmetic,
  /// when that time is an irrational square root, a rational lower bound of it.
  struct Closing {
    S time;
    bool bound = false;
  };
  /// When contact c (bodies c, c+1) closes from now; nothing when it does not.
  std::optional<Closing> closing_time(int c) const {
    if (supported_[c]) return std::nullopt;
    const S d = v_[c] - v_[c + 1], gap = gap_[c];
    if (!supported_[c + 1]) {  // both free: linear
      if (d < S(0)) return Closing{S(gap / -d)};
      return std::nullopt;
    }
    // Over the held bodies: gap + d t − g t²/2 = 0, the positive root in a stable form.
    if (gap == S(0)) return Closing{d > S(0) ? S(2 * d / g_) : S(0)};
    const S square = d * d + 2 * g_ * gap;
    if constexpr (T::exact) {
      S root;
      if (cln::sqrtp(square, &root)) return Closing{d > S(0) ? S((d + root) / g_) : S(2 * gap / (root - d))};
      const auto [low, high] = sqrt_bounds(square);
      return Closing{d > S(0) ? S((d + low) / g_) : S(2 * gap / (high - d)), true};
    } else {
      using std::sqrt;
      const S root = sqrt(square);
      return Closing{d > S(0) ? S((d + root) / g_) : S(2 * gap / (root - d))};
    }
  }

  /// The next event: whether any contact closes, its delay, the contacts
  /// that close then (ties together), how many other contacts closed within
  /// the tie and the doubt bounds of it, and (exact arithmetic) whether its
  /// time is not rational, or too near one that is not to be ordered.
  struct Next {
    bool any = false;
    S delay = S(0);
    std::vector<int> closing;
    int ties = 0, near_ties = 0;
    bool inexact = false;
  };
  Next next_event() const {
    std::vector<std::optional<Closing>> times(static_cast<std::size_t>(n_ - 1));
    Next next;
    for (int c = 0; c + 1 < n_; ++c) {
      times[c] = closing_time(c);
      if (times[c] && (!next.any || times[c]->time < next.delay)) next.delay = times[c]->time, next.any = true;
    }
    if (!next.any) return next;
    const S first = next.delay;
    S tie = S(0), doubt = S(0);
    if constexpr (!T::exact) {
      const S scale = std::max(S(t_ + first), time_scale_);
      tie = S(drop_tie_ulps) * u_ * scale, doubt = S(drop_doubt_ulps) * u_ * scale;
    }
    for (int c = 0; c + 1 < n_; ++c) {
      if (!times[c]) continue;
      if (times[c]->bound && times[c]->time <= first) next.inexact = true;  // (a lower bound: its time may be the first)
      if (times[c]->time - first <= tie) {
        next.closing.push_back(c);
      } else if (times[c]->time - first <= doubt) {
        ++next.near_ties;
      }
    }
    next.ties = static_cast<int>(next.closing.size()) - 1;
    return next;
  }

  /// Whether the run's time \p s (in the run's units) is past the scene's until.
  bool beyond_until(const S& s) const {
    if (a2_) return s > S(0) && s * s > *a2_ * *until_ * *until_;  // s > a·until
    return s > *until_;
  }

  /// Ends the run at the scene's until.  In the units of a rational run that
  /// instant (a·until) is not rational: it ends there without the last
  /// flight, which nothing reported needs.
  void end_at_until() {
    if (!a2_) advance(*until_ - t_);
    end("until");
    if (a2_) r_.end_time = T::to_double(*until_);
  }

  ///@{
  /// A time, a speed (or momentum) and an energy of the run in SI units.
  double si_time(const S& t) const { return T::to_double(t) / a_; }
  double si_speed(const S& v) const { return T::to_double(v) * a_; }
  double si_energy(const S& e) const { return T::to_double(e) * (a_ * a_); }
  ///@}

  /// Every body's flight over \p dt.
  void advance(S dt) {
    if (dt <= S(0)) return;
    for (int c = 0; c + 1 < n_; ++c) gap_[c] += (v_[c] - v_[c + 1]) * dt + (acceleration(c) - acceleration(c + 1)) * dt * dt / 2;
    for (int i = 0; i < n_; ++i) {
      if (supported_[i]) continue;
      z_[i] += v_[i] * dt - g_ * dt * dt / 2;
      v_[i] -= g_ * dt;
    }
    t_ += dt;
  }

  bool touching(int c) const { return gap_[c] == S(0) && v_[c] - v_[c + 1] <= S(0); }

  /// The collisions of the contacts in \p closing (\p certified: their order
  /// against every other contact is certified); false when a solve fails.
  /// Touching view: each run of touching contacts that holds a closing one
  /// collides, M restricted to it.  Distant view: each set of bodies joined
  /// by M's pairs and by touching contacts that holds a closing one
  /// collides, every pair of M among them acting, impenetrability on its
  /// touching contacts only.
  bool collide(const std::vector<int>& closing, bool certified) {
    for (int c : closing) gap_[c] = S(0);
    std::vector<bool> closes(static_cast<std::size_t>(n_ - 1), false);
    for (int c : closing) closes[c] = true;
    const std::vector<System> systems = distant_ ? distant_systems(closes) : touching_clusters(closes);
    for (const System& system : systems)
      if (!collide_system(system, closes, certified)) return false;
    settle();
    return true;
  }

  /// The bodies of one collision: p … q, those of them that take part
  /// (\p member, over all n bodies; an entry of M acts when its bodies all
  /// do) and the contacts c of p … q under impenetrability (\p constrained,
  /// c − p; empty: every one).
  struct System {
    int p = 0, q = 0;
    std::vector<bool> member;
    std::vector<char> constrained;
  };

  /// The runs of touching contacts that hold a contact of \p closes (the touching view).
  std::vector<System> touching_clusters(const std::vector<bool>& closes) const {
    std::vector<System> systems;
    for (int c = 0; c + 1 < n_;) {
      if (!touching(c)) {
        ++c;
        continue;
      }
      int last = c;  // the run of touching contacts c … last
      bool any = false;
      for (; last + 1 < n_ && touching(last); ++last) any = any || closes[last];
      if (any) {
        System s;
        s.p = c, s.q = last;
        s.member.assign(static_cast<std::size_t>(n_), false);
        for (int i = c; i <= last; ++i) s.member[i] = true;
        systems.push_back(std::move(s));
      }
      c = last + 1;
    }
    return systems;
  }

  /// The sets of bodies joined by M's pairs and the touching contacts that
  /// hold a contact of \p closes, top to bottom (the distant view).
  std::vector<System> distant_systems(const std::vector<bool>& closes) const {
    std::vector<int> group = m_group_;
    const auto root = [&group](int i) {
      while (group[i] != i) i = group[i] = group[group[i]];
      return i;
    };
    for (int c = 0; c + 1 < n_; ++c)
      if (touching(c)) group[root(c)] = root(c + 1);
    std::vector<System> systems;
    std::vector<bool> done(static_cast<std::size_t>(n_), false);
    for (int c = 0; c + 1 < n_; ++c) {
      const int r = root(c);
      if (!closes[c] || done[r]) continue;
      done[r] = true;
      System s;
      s.member.assign(static_cast<std::size_t>(n_), false);
      s.p = n_, s.q = -1;
      for (int i = 0; i < n_; ++i)
        if (root(i) == r) s.member[i] = true, s.p = std::min(s.p, i), s.q = std::max(s.q, i);
      bool every = true;
      for (int k = s.p; k < s.q; ++k) {
        const bool on = touching(k) && s.member[k] && s.member[k + 1];
        s.constrained.push_back(on ? 1 : 0);
        every = every && on;
      }
      if (every) s.constrained.clear();  // all touching: the problem of the touching view, solved as it is
      systems.push_back(std::move(s));
    }
    return systems;
  }

  /// The collision of \p system.
  bool collide_system(const System& system, const std::vector<bool>& closes, bool certified) {
    const int p = system.p, q = system.q;
    const std::vector<bool>& member = system.member;
    Problem<S> sub;
    sub.n = q - p + 1;
    sub.fixed_bottom = obstacle(q);
    sub.in_range = full_.in_range;
    sub.digits = full_.digits;
    sub.constrained = system.constrained;
    for (int i = p; i <= q; ++i) {
      sub.mass.push_back(full_.mass[i]);
      sub.u.push_back(v_[i]);
    }
    for (const Entry<S>& e : full_.entries)
      if (member[e.i] && member[e.j] && member[e.k] && member[e.l]) sub.entries.push_back({e.i - p, e.j - p, e.k - p, e.l - p, e.value});
    const Solution<S> sol = solve_collision(sub);
    DropEvent ev;
    ev.time = si_time(t_);
    for (int c = p; c < q; ++c)
      if (closes[c]) ev.contacts.push_back(Pair{c + 1, c + 2}.name());
    ev.first_body = p + 1;
    ev.last_body = q + 1;
    ev.order_certified = certified;
    for (int c = p; c < q; ++c)
      if (!sub.constrained_contact(c - p)) ev.apart.push_back(Pair{c + 1, c + 2}.name());
    for (int i = 0; i < n_; ++i) {
      ev.velocities_before.push_back(si_speed(v_[i]));
      ev.heights.push_back(T::to_double(z_[i]));
    }
    ev.kinetic_energy_before = kinetic();
    v_before_ = v_;
    if (sol.status != Status::Success) {
      r_.events.push_back(ev);
      return false;
    }
    S momentum_before = S(0), momentum_after = S(0), speed = S(0);
    for (int i = p; i <= q; ++i) {
      if (!member[i]) continue;
      const bool finite = !obstacle(i);
      if (finite) momentum_before += full_.mass[i] * v_[i];
      speed = std::max({speed, magnitude(v_[i]), magnitude(sol.velocities_after[i - p])});
      if (finite) v_[i] = sol.velocities_after[i - p];
    }
    // Contacts that stay closed move as one: the group's velocity (its
    // momentum over its mass, 0 on the obstacle).  Only constrained contacts
    // can: an open one stays apart whatever its bodies' velocities.
    ContactSet whole(n_);
    for (int c = p; c < q; ++c) {
      const bool closed = sub.constrained_contact(c - p) &&
                          (sol.closed.closed(c - p) || magnitude(S(v_[c] - v_[c + 1])) <= closed_ulps() * u_ * speed);
      whole.set_closed(c, closed);
    }
    for (int a = p; a <= q;) {
      int b = a;
      while (b < q && whole.closed(b)) ++b;
      if (b > a) {
        const bool on_obstacle = obstacle(b);
        S m = S(0), mv = S(0);
        for (int i = a; i <= b; ++i)
          if (!obstacle(i)) m += full_.mass[i], mv += full_.mass[i] * v_[i];
        const S common = on_obstacle ? S(0) : S(mv / m);
        for (int i = a; i <= b; ++i)
          if (!obstacle(i)) v_[i] = common;
      }
      a = b + 1;
    }
    const std::vector<bool> was_supported = supported_;
    for (int i = p; i <= q; ++i) {
      if (!member[i]) continue;
      if (!obstacle(i)) momentum_after += full_.mass[i] * v_[i];
      last_t_[i] = t_;
      last_z_[i] = z_[i];
      last_v_[i] = v_[i];
      if (!obstacle(i)) supported_[i] = false;
    }
    for (int c = p; c < q; ++c)
      if (whole.closed(c)) ev.closed.push_back(Pair{c + 1, c + 2}.name());
    const Vocabulary& paper = Vocabulary::paper();
    if (sub.n == n_ && n_ == paper.bodies() && sub.constrained.empty() && std::all_of(member.begin(), member.end(), [](bool m) { return m; })) {
      ev.case_name = paper.case_name(whole);
    } else {
      std::string set;
      for (const auto& c : ev.closed) set += (set.empty() ? "" : ",") + c;
      ev.case_name = "{" + set + "}";
    }
    for (int i = 0; i < n_; ++i) ev.velocities_after.push_back(si_speed(v_[i]));
    ev.kinetic_energy_after = kinetic();
    ev.momentum_before = si_speed(momentum_before);
    ev.momentum_after = si_speed(momentum_after);
    r_.events.push_back(ev);
    // The bodies this collision leaves at rest on the obstacle (directly or on
    // bodies resting there) that were not resting before: each is said once.
    if (obstacle(q)) {
      for (int i = q - 1; i >= p && whole.closed(i) && v_[i] == S(0); --i) {
        z_[i] = last_z_[i] = z_[q];  // on the obstacle, not a rounding below it
        if (!was_supported[i]) r_.rest.push_back({i + 1, ev.time, false, 0});
      }
    }
    return true;
  }

  S kinetic_energy() const {
    S e = S(0);
    for (int i = 0; i < n_; ++i)
      if (!obstacle(i)) e += full_.mass[i] * v_[i] * v_[i] / 2;
    return e;
  }
  double kinetic() const { return si_energy(kinetic_energy()); }

  static S magnitude(const S& x) {
    using std::abs;
    return abs(x);
  }
  /// drop_closed_ulps in S (0 in exact arithmetic, whose u is 0).
  static S closed_ulps() {
    if constexpr (T::exact) {
      return S(0);
    } else {
      return S(drop_closed_ulps);
    }
  }

  /// After a bounce of the lowest free body b on the fixed obstacle, or on
  /// the bodies at rest on it (every body below b held), with the bodies
  /// a … b−1 that touch it and move with it as one (a stack bouncing whole:
  /// its law is linear, so its speeds too are geometric): when nothing else
  /// can touch them before their bounces accumulate, they rest there at the
  /// sum of the geometric series (and no later than the scene's until).
  void accumulate() {
    if (!fixed_ || r_.events.empty()) return;
    const DropEvent& ev = r_.events.back();
    int b = n_ - 2;
    while (b >= 0 && supported_[b]) --b;
    // Bodies a … b−1 touching b and moving with it before and after (a stack bouncing as one) bounce with it.
    int a = b;
    while (a > 0 && a > ev.first_body - 1 && gap_[a - 1] == S(0) && v_[a - 1] == v_[b] && v_before_[a - 1] == v_before_[b]) --a;
    if (b < 0 || ev.first_body != a + 1 || ev.last_body != n_ || ev.time != si_time(t_)) return;
    const S before = -v_before_[b], after = v_[b];
    if (!(after > S(0)) || !(before > S(0))) return;
    const S e = after / before;
    if (!(e < S(1))) return;
    // Bounces are followed one by one down to drop_rest_fraction of the release height.
    if (S(after * after / (2 * g_)) > rest_height_) return;
    const S span = (2 * after / g_) / (1 - e);
    if (until_ && beyond_until(t_ + span)) return;
    // The top body's apex comes first: the run ends there.
    if (a != 0 && !supported_[0] && v_[0] > S(0) && S(v_[0] / g_) < span && !until_) return;
    if (a == 0 && !until_) return;
    // Nothing above may close before: the contacts above a in free flight,
    // and body a−1 stays over the highest arc of a (a concave flight's
    // minimum over an interval is at one of its ends).
    for (int c = 0; c + 1 < a; ++c) {
      const std::optional<Closing> closes = closing_time(c);
      if (closes && closes->time <= span) return;
    }
    if (a >= 1) {
      const S apex = after * after / (2 * g_);
      const S w = v_[a - 1];
      const S at_end = gap_[a - 1] + w * span - g_ * span * span / 2;
      if (!(gap_[a - 1] > apex) || !(at_end > apex)) return;
    }
    const double e_double = T::to_double(e);
    for (int i = b; i >= a; --i) {
      v_[i] = S(0);
      z_[i] = z_[b + 1];
      gap_[i] = S(0);
      supported_[i] = true;
    }
    advance(span);
    for (int i = b; i >= a; --i) {
      last_t_[i] = t_;
      last_z_[i] = z_[i];
      last_v_[i] = S(0);
      r_.rest.push_back({i + 1, si_time(t_), true, e_double});
    }
  }

  void end(const char* why) {
    r_.end = why;
    r_.end_time = si_time(t_);
    r_.ties = ties_;
    r_.near_ties = near_ties_;
    r_.orders_certified = T::exact || (ties_ == 0 && near_ties_ == 0);  // exact: ties are exact
    for (int i = 0; i < n_; ++i) {
      if (obstacle(i)) continue;
      const S up = last_v_[i] > S(0) ? last_v_[i] : S(0);
      r_.apexes.push_back({i + 1, T::to_double(S(last_z_[i] + up * up / (2 * g_))), si_time(S(last_t_[i] + up / g_))});
    }
    const double h0 = r_.release_heights[0];
    r_.top_apex_ratio = r_.apexes.empty() ? 0 : h0 > 0 ? r_.apexes[0].height / h0 : std::numeric_limits<double>::infinity();
  }

  const Scene& scene_;
  int digits_;  ///< digits:N's N (0 in the other arithmetics)
  Problem<S> full_;
  int n_;
  bool fixed_;
  bool distant_;  ///< [drop] distant = true: every pair of M in every collision
  /// Bodies joined by M's nonzero entries (an entry couples the bodies of its two pairs): union-find parents.
  std::vector<int> m_group_;
  S g_, u_, t_ = S(0), time_scale_ = S(1);
  S rest_height_;  ///< drop_rest_fraction of the top body's release height: bounces below it are summed
  std::optional<S> until_;  ///< the scene's until (s), none: to the top body's apex
  /// A rational run's unit of speed squared, a² = 2·g·h (m²/s²), and a in double; none and 1 otherwise.
  std::optional<S> a2_;
  double a_ = 1;
  std::vector<S> z_, v_, gap_, v_before_;
  std::vector<bool> supported_;
  std::vector<S> last_t_, last_z_, last_v_;  ///< each body's state after its last collision (or release)
  int ties_ = 0, near_ties_ = 0;
  DropResult r_;
};

/// Refuses a datum of the drop (g, drop_height, a gap, a velocity, a mass,
/// until, the top body's release height) that is not 0 and lies outside the window
/// [2^−w, 2^w] of the run's arithmetic (w = safe_exponent<S>() of double or
/// long double; double's for digits:N and exact, whose report is in double),
/// where the flights' products (v², 2·g·h, g·t²) stay finite and a nonzero
/// datum stays nonzero:
/// std::invalid_argument("drop(): SCENE: FIELD = VALUE is outside ...").
void check_window(const Scene& scene, const Precision& precision) {
  const int w = precision.kind == Precision::Kind::LongDouble ? safe_exponent<long double>() : safe_exponent<double>();
  const cln::cl_RA low = cln::expt(cln::cl_RA(2), -w), high = cln::expt(cln::cl_RA(2), w);
  auto check = [&](const cln::cl_RA& x, const std::string& field, const std::string& text) {
    if (cln::zerop(x) || (cln::abs(x) >= low && cln::abs(x) <= high)) return;
    std::ostringstream range;
    range.precision(2);
    range << std::ldexp(1.0L, -w) << " to " << std::ldexp(1.0L, w);
    throw std::invalid_argument("drop(): " + scene.origin + ": " + field + " = " + text + " is outside what a drop in " + precision.name() +
                                " computes with (0, or " + range.str() + " in magnitude" +
                                (precision.kind == Precision::Kind::Double ? "; long-double takes more)" : ")"));
  };
  auto value = [](const Number& x) { return parse_rational(x.fraction()); };
  check(value(scene.g), "g", scene.g.text);
  cln::cl_RA top = 0;
  if (scene.drop_height) check(top = value(*scene.drop_height), "drop_height", scene.drop_height->text);
  if (scene.drop.until) check(value(*scene.drop.until), "drop.until", scene.drop.until->text);
  for (std::size_t k = scene.bodies.size(); k-- > 0;) {
    const Body& b = scene.bodies[k];
    const std::string field = "body[" + std::to_string(k + 1) + "].";
    if (b.gap) check(value(*b.gap), field + "gap", b.gap->text), top = top + value(*b.gap);
    if (b.velocity && !b.infinite) check(value(*b.velocity), field + "velocity", b.velocity->text);
    if (!b.infinite) check(value(b.mass), field + "mass", b.mass.text);  // the energies m·v² are not scaled
  }
  check(top, "the top body's release height", to_string(cln::cl_R(top), 6));
}

}  // namespace

bool drop_finished(const std::string& end) { return end != "max-events" && end != "numerical-issue" && end != "inexact"; }

DropResult drop(const Scene& scene, const Precision& precision) {
  if (!scene.drop.requested) throw InputError(scene.origin + ": has no [drop] table: superball drop follows a scene's [drop]");
  // The checks of a scene (M positive semi-definite, masses), on the bodies at rest.
  Scene still = scene;
  still.drop_height.reset();
  still.fall_speed.reset();
  for (Body& b : still.bodies) b.velocity = Number::integer(0);
  const ExactScene exact = ExactScene::from(still);
  check_window(scene, precision);
  switch (precision.kind) {
    case Precision::Kind::Double: return DropRun<double>(scene, exact, precision.name(), 0).run();
    case Precision::Kind::LongDouble: return DropRun<long double>(scene, exact, precision.name(), 0).run();
    case Precision::Kind::Digits: return DropRun<MpFloat>(scene, exact, precision.name(), precision.digits).run();
    case Precision::Kind::Exact: break;
  }
  return DropRun<cln::cl_RA>(scene, exact, precision.name(), 0).run();
}

DropResult drop(const Scene& scene, const SolvePrecision& precision) {
  if (!precision.automatic) return drop(scene, precision.fixed);
  if (precision.rtol)
    throw std::invalid_argument("drop(): precision auto takes no rtol: a drop's auto runs again in long double when an order of "
                                "events is not certified");
  Precision p;
  DropResult in_double = drop(scene, p);
  if (in_double.orders_certified) {
    in_double.precision_asked = "auto";
    return in_double;
  }
  p.kind = Precision::Kind::LongDouble;
  DropResult r = drop(scene, p);
  if (!r.orders_certified) {  // exact, when it goes the whole way (every event's time rational)
    p.kind = Precision::Kind::Exact;
    DropResult exact = drop(scene, p);
    if (exact.end != "inexact" && exact.end != "numerical-issue") r = std::move(exact);
  }
  r.precision_asked = "auto";
  r.escalated = true;
  r.double_events = static_cast<int>(in_double.events.size());
  r.sequences_agree = same_sequence(in_double, r);
  return r;
}

}  // namespace superball::numeric
