#!/usr/bin/env python3
"""SymPy reference for `superball derive --all`: the same derivation as
symbolic/src/derivation.cpp, written with SymPy (Debian's python3-sympy), to
time it against the GiNaC implementation (bench/bench_symbolic.cpp).

Per case: clusters of bodies joined by closed contacts, the reduced system
(Z^T A Z) V = Z^T b solved by Cramer's rule with fraction-free determinants
(det(Z^T A Z) > 0), velocities and reactions in lowest terms (cancel), the
substitution check in the unreduced equations, then the conditions
(superball, evolution, contact) with one cancel per condition, the
denominator's sign from "divides det(Z^T A Z)" plus its value at the
reference point, positive content and monomial removed, the asymptotic
dominant balance for m1 ~ eps, K_1n ~ 1/eps (m_n ~ 1/eps when finite), and the
principal minors of M over connected sets of pairs.

Usage:
    python3 bench/sympy_reference.py                 # all benchmarks, timings
    python3 bench/sympy_reference.py --only n4_all_alphas/fixed --repeat 3
"""
import argparse
import itertools
import signal
import sys
import time

import sympy as sp

# The paper's alpha_k (cases/paper/vocabulary.toml): the two pairs each couples.
PAPER_ALPHAS = {1: ((1, 2), (1, 3)), 2: ((1, 2), (1, 4)), 3: ((1, 3), (1, 4)), 4: ((1, 4), (2, 3)),
                5: ((1, 4), (2, 4)), 6: ((2, 3), (2, 4)), 7: ((1, 4), (3, 4))}


def code(p):
    i, j = p
    return f"{i}{j}" if i < 10 and j < 10 else f"{i}_{j}"


class Pattern:
    def __init__(self, n, diagonal, couplings, names=None):
        self.n, self.diagonal, self.couplings = n, sorted(diagonal), sorted(couplings)
        self.names = names or {}

    @staticmethod
    def paper(alphas):
        diagonal = [(i, j) for i in range(1, 5) for j in range(i + 1, 5)]
        return Pattern(4, diagonal, [PAPER_ALPHAS[k] for k in alphas], {PAPER_ALPHAS[k]: f"alpha{k}" for k in alphas})

    @staticmethod
    def nearest_and_next_nearest(n):
        diagonal = [(i, j) for i in range(1, n + 1) for j in range(i + 1, n + 1) if j - i <= 2]
        couplings = []
        for i in range(1, n - 1):
            couplings += [((i, i + 1), (i, i + 2)), ((i, i + 2), (i + 1, i + 2))]
        return Pattern(n, diagonal, couplings)


class Deriver:
    def __init__(self, pattern, finite):
        self.p, self.finite = pattern, finite
        n = pattern.n
        self.m = [sp.Symbol(f"m{i}", positive=True) for i in range(1, n + (1 if finite else 0))]
        self.K = {p: sp.Symbol("K" + code(p), positive=True) for p in pattern.diagonal}
        self.c = {pq: sp.Symbol(pattern.names.get(pq, f"c_{code(pq[0])}_{code(pq[1])}"), real=True) for pq in pattern.couplings}
        self.a = sp.Symbol("a", positive=True)
        self.all_symbols = self.m + list(self.K.values()) + list(self.c.values()) + [self.a]
        self.coupling_symbols = set(self.c.values())
        self.reference = {s: (0 if s in self.coupling_symbols else 1) for s in self.all_symbols}
        self.order = {self.m[0]: 1}
        if finite:
            self.order[self.m[n - 1]] = -1
        if (1, n) in self.K:
            self.order[self.K[(1, n)]] = -1
        # K = D^T M D over the declared entries only.
        self.Kmat = sp.zeros(n, n)
        def outer(p, q, v):
            (pi, pj), (qi, qj) = p, q
            for r, sr in ((pi, 1), (pj, -1)):
                for s, ss in ((qi, 1), (qj, -1)):
                    self.Kmat[r - 1, s - 1] += sr * ss * v
        for p, v in self.K.items():
            outer(p, p, v)
        for (p, q), v in self.c.items():
            outer(p, q, v)
            outer(q, p, v)
        self.psd = self.psd_conditions()

    # -- polynomials ---------------------------------------------------------------
    def weight(self, monom, gens):
        return sum(e * self.order.get(g, 0) for g, e in zip(gens, monom))

    def strip(self, expr):
        """Positive content and common monomial of positive symbols removed."""
        expr = sp.expand(expr)
        if expr == 0:
            return expr
        poly = sp.Poly(expr, *self.all_symbols)
        content, prim = poly.primitive()
        monomial = [min(mon[k] for mon in prim.monoms()) for k in range(len(self.all_symbols))]
        for k, s in enumerate(self.all_symbols):
            if s in self.coupling_symbols:
                monomial[k] = 0
        factor = sp.Mul(*[s ** e for s, e in zip(self.all_symbols, monomial)])
        q, r = sp.div(prim.as_expr(), factor, *self.all_symbols)
        assert r == 0
        return sp.expand(q)

    def asymptotic(self, expr):
        expr = sp.expand(expr)
        if expr == 0:
            return expr
        poly = sp.Poly(expr, *self.all_symbols)
        levels = {}
        for monom, coeff in poly.terms():
            w = self.weight(monom, self.all_symbols)
            levels[w] = levels.get(w, 0) + coeff * sp.Mul(*[s ** e for s, e in zip(self.all_symbols, monom)])
        return self.strip(levels[min(levels)])

    def condition(self, raw, det):
        num, den = sp.fraction(sp.cancel(raw / det))  # one cancel per condition
        q, r = sp.div(det, den, *self.all_symbols)
        if r != 0:
            return ("sign not proved", num, den)
        sign = 1 if den.subs(self.reference) > 0 else -1
        exact = self.strip(sign * num)
        if self.finite:
            exact = self.strip(sp.Poly(exact, self.m[-1]).LC())
        return ("proved", exact, self.asymptotic(exact))

    def psd_conditions(self):
        pairs = sorted(set(self.p.diagonal) | {x for pq in self.p.couplings for x in pq})
        adjacent = {p: set() for p in pairs}
        for p, q in self.p.couplings:
            adjacent[p].add(q)
            adjacent[q].add(p)
        def entry(p, q):
            if p == q:
                return self.K.get(p, 0)
            return self.c.get((p, q), self.c.get((q, p), 0))
        out = []
        for size in range(1, len(pairs) + 1):
            for subset in itertools.combinations(pairs, size):
                seen, todo = {subset[0]}, [subset[0]]
                while todo:
                    x = todo.pop()
                    for y in adjacent[x]:
                        if y in subset and y not in seen:
                            seen.add(y)
                            todo.append(y)
                if len(seen) != size:
                    continue
                minor = sp.expand(sp.Matrix(size, size, lambda r, c: entry(subset[r], subset[c])).det(method="berkowitz"))
                if minor != 0:
                    out.append((subset, minor, self.asymptotic(minor)))
        return out

    # -- one case ------------------------------------------------------------------
    def derive(self, closed):
        n, m, K, a = self.p.n, self.m, self.Kmat, self.a
        fixed = not self.finite
        free = n - 1 if fixed else n
        cluster, top = [0] * n, [0]
        for i in range(1, n):
            if not closed[i - 1]:
                top.append(i)
            cluster[i] = len(top) - 1
        fixed_cluster = cluster[n - 1] if fixed else -1
        k = len(top) - 1 if fixed else len(top)
        u = [-a] * (n - 1) + [0]
        mass = lambda i: m[i] if i < free else 0
        B, rhs = sp.zeros(k, k), sp.zeros(k, 1)
        for i in range(free):
            ci = cluster[i]
            if ci == fixed_cluster:
                continue
            r = mass(i) * u[i]
            for j in range(n):
                r -= K[i, j] * u[j]
                cj = cluster[j]
                if cj == fixed_cluster:
                    r -= K[i, j] * u[n - 1]
                else:
                    B[ci, cj] += K[i, j] + (mass(i) if i == j else 0)
            rhs[ci] += r
        det = sp.expand(B.det(method="berkowitz")) if k else sp.Integer(1)
        V = []
        for c in range(k):
            Bc = B.copy()
            Bc[:, c] = rhs
            V.append(sp.expand(Bc.det(method="berkowitz")))
        W = [V[cluster[i]] if cluster[i] != fixed_cluster else u[n - 1] * det for i in range(n)]
        L = [0] * (n - 1)
        for c in range(n - 1):
            if closed[c]:
                s = 0
                for i in range(top[cluster[c]], c + 1):
                    s += mass(i) * (W[i] - u[i] * det) + sum(K[i, j] * (W[j] + u[j] * det) for j in range(n))
                L[c] = sp.expand(s)
        velocities = [sp.cancel(w / det) for w in W]
        reactions = [sp.cancel(-l / det) for l in L]
        # Substitution check in the unreduced equations.
        for i in range(free):
            r = mass(i) * (velocities[i] - u[i]) + sum(K[i, j] * (velocities[j] + u[j]) for j in range(n))
            if i + 1 < n:
                r += reactions[i]
            if i > 0:
                r -= reactions[i - 1]
            if sp.cancel(r) != 0:
                raise RuntimeError(f"substitution check failed, body {i + 1}")
        conditions = [("superball", self.condition(W[0] - a * det, det))]
        for c in range(n - 1):
            if not closed[c]:
                conditions.append((f"evolution {c + 1}-{c + 2}", self.condition(W[c] - W[c + 1], det)))
        for c in range(n - 1):
            if closed[c]:
                conditions.append((f"contact {c + 1}-{c + 2}", self.condition(L[c], det)))
        return velocities, reactions, conditions + [("psd", x) for x in self.psd]

    def derive_all(self):
        n = self.p.n
        return [self.derive([(mask >> c) & 1 == 1 for c in range(n - 1)]) for mask in range(1 << (n - 1))]


BENCHMARKS = {
    "n4_all_alphas/fixed": lambda: Deriver(Pattern.paper([1, 2, 3, 4, 5, 6, 7]), False).derive_all(),
    "n4_all_alphas/finite": lambda: Deriver(Pattern.paper([1, 2, 3, 4, 5, 6, 7]), True).derive_all(),
    "n5_nnn/fixed": lambda: Deriver(Pattern.nearest_and_next_nearest(5), False).derive_all(),
    "n5_nnn/finite": lambda: Deriver(Pattern.nearest_and_next_nearest(5), True).derive_all(),
    "case1_alpha2/fixed": lambda: Deriver(Pattern.paper([2]), False).derive([False, True, True]),
}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--only", action="append", help="run only this benchmark (repeatable): " + ", ".join(BENCHMARKS))
    parser.add_argument("--repeat", type=int, default=1, help="repetitions; the median is reported")
    parser.add_argument("--timeout", type=int, default=0, help="give up a benchmark after this many seconds (0: never)")
    args = parser.parse_args()
    names = args.only or list(BENCHMARKS)
    for name in names:
        if name not in BENCHMARKS:
            sys.exit(f"sympy_reference.py: no benchmark '{name}' (have: {', '.join(BENCHMARKS)})")
    print(f"SymPy {sp.__version__}, Python {sys.version.split()[0]}")
    # Sanity: the paper's case 1 with alpha_2 (§4.1).
    v, _, conds = BENCHMARKS["case1_alpha2/fixed"]()
    print("case 1, alpha2: U1 =", v[0], "; superball:", conds[0][1][1], "> 0")
    def give_up(signum, frame):
        raise TimeoutError
    signal.signal(signal.SIGALRM, give_up)
    for name in names:
        times = []
        try:
            for _ in range(args.repeat):
                signal.alarm(args.timeout)
                t0 = time.perf_counter()
                BENCHMARKS[name]()
                times.append(time.perf_counter() - t0)
                signal.alarm(0)
        except TimeoutError:
            print(f"{name:28s} did not finish in {args.timeout} s", flush=True)
            continue
        times.sort()
        print(f"{name:28s} median {1000 * times[len(times) // 2]:12.1f} ms over {len(times)} run(s)", flush=True)


if __name__ == "__main__":
    main()
