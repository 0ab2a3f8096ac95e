#pragma once
// Internal: the dense steps that CollisionSolver's general path
// (collision.cpp, Eigen matrices) and its fixed-size path (small_solver.cpp,
// arrays of compile-time size) share: one template each, over the storage
// (anything with A(i, j) and x(i) giving the element), so that both paths
// perform the same operations in the same order and agree bit for bit
// (tests/numeric/small_solver_test.cpp).

#include "collision/mpfloat_steps.hpp"

namespace superball::numeric::detail {

///@{
/// x += a·b, x −= a·b and x += a·b/2, the product rounded then the sum: the expression
/// itself for double and the other types (the same operations in the same
/// order); for MpFloat, argument-dependent lookup takes the overloads of
/// mpfloat_steps.hpp, the same roundings without a temporary number.
template <class X, class A, class B>
inline void add_product(X& x, const A& a, const B& b) {
  x += a * b;
}
template <class X, class A, class B>
inline void subtract_product(X& x, const A& a, const B& b) {
  x -= a * b;
}
/// x += a·b/2: x += a * b / X(2).
template <class X, class A, class B>
inline void add_half_product(X& x, const A& a, const B& b) {
  x += a * b / X(2);
}
///@}

/// The decisions of a step on one problem: each branch is taken on its
/// condition.  The fixed-size path in lanes (small.hpp, LaneFlow) solves
/// several problems at once through the same templates: there a condition
/// holds per lane, and fails() / leader() say which lanes go on.
struct OneProblem {
  /// A branch that gives up on the problem (the step returns false).
  static bool fails(bool condition) { return condition; }
  /// A branch that chooses what the step does next.
  static bool leader(bool condition) { return condition; }
};

/// The LDLᵀ factors of the symmetric \p nf × \p nf matrix whose lower
/// triangle \p A holds, in place and without pivoting (A = diag(m) + DᵀMD on
/// the free bodies is positive definite when M is positive semi-definite): L
/// below the diagonal, D on it.  False at the first pivot that is not
/// positive, with no division by it (CLN floats throw on 0), the factors
/// then partial.  \p flow takes the decisions (OneProblem).
template <class S, class Matrix, class Flow = OneProblem>
bool ldlt_in_place(Matrix& A, int nf, Flow&& flow = Flow{}) {
  for (int k = 0; k < nf; ++k) {
    const S d = A(k, k);
    if (flow.fails(!(d > S(0)))) return false;
    for (int j = k + 1; j < nf; ++j) {
      const S ljk = A(j, k) / d;
      for (int i = j; i < nf; ++i) subtract_product(A(i, j), A(i, k), ljk);
    }
    for (int i = k + 1; i < nf; ++i) A(i, k) /= d;
  }
  return true;
}

/// x := A⁻¹x for the factors of ldlt_in_place() in \p A (\p nf unknowns).
template <class Matrix, class Vector>
void ldlt_solve_in_place(const Matrix& A, int nf, Vector&& x) {
  for (int i = 1; i < nf; ++i)
    for (int k = 0; k < i; ++k) subtract_product(x(i), A(i, k), x(k));
  for (int i = 0; i < nf; ++i) x(i) /= A(i, i);
  for (int i = nf - 2; i >= 0; --i)
    for (int k = i + 1; k < nf; ++k) subtract_product(x(i), A(k, i), x(k));
}

/// The principal pivot transform on (p, p) of the tableau w = t + Tλ of
/// \p nc contacts: exchanges the basic and the non-basic variable of contact
/// \p p, an O(nc²) update of \p T and \p t in place (Murty's pivoting step).
/// False, with both unchanged, when T(p, p) is not positive.  \p flow
/// takes the decisions (OneProblem).
template <class S, class Tableau, class Column, class Flow = OneProblem>
bool principal_pivot(Tableau& T, Column& t, int nc, int p, Flow&& flow = Flow{}) {
  const S piv = T(p, p);
  if (flow.fails(!(piv > S(0)))) return false;
  for (int i = 0; i < nc; ++i) {
    if (i == p) continue;
    const S f = T(i, p) / piv;
    if (flow.leader(f == S(0))) continue;
    for (int j = 0; j < nc; ++j)
      if (j != p) subtract_product(T(i, j), f, T(p, j));
    subtract_product(t(i), f, t(p));
    T(i, p) = f;
  }
  for (int j = 0; j < nc; ++j)
    if (j != p) T(p, j) = -T(p, j) / piv;
  T(p, p) = S(1) / piv;
  t(p) = -t(p) / piv;
  return true;
}

}  // namespace superball::numeric::detail
