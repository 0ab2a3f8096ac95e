#!/usr/bin/env python3
"""Readability of `superball derive` text output, measured as issue 13 asks.

For every "asymptotic:" line: the characters of the formula after
"asymptotic:" (the bracketed note excluded) plus those of the named parts
(S1 = ...) of the same case that the formula uses.  Prints the count, the
median, the 90th percentile and the longest, and the longest line of the
whole output.

    superball derive --bodies 6 --pairs near2 --coupling near2 --all > d6.txt
    python3 bench/readability.py d6.txt [--skip-psd]

--skip-psd leaves out the positive semi-definiteness minors (the same in
every case).  Characters are Unicode code points (m₁ is two).

A long case is written through its elimination (p₅ = …, l₄₅ = …, y₅ = …,
V₁ = y₁/p₁ under "elimination:"), and its conditions through the cluster
velocities (V₄ > V₅).  Two counts are printed: the issue's (the formula and
the named parts S it uses), and the same plus every elimination definition
the formula depends on, directly or through other definitions (what a reader
must read to expand the condition by hand).
"""
import re
import sys


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    skip_psd = "--skip-psd" in sys.argv
    if len(args) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    text = open(args[0], encoding="utf-8").read()
    lines = text.split("\n")
    named = {}  # name -> definition length, per case
    definitions = {}  # elimination name -> (length, names it uses), per case
    sizes, closures = [], []
    title = ""
    for line in lines:
        if line and not line.startswith(" "):  # a case title
            named = {}
            definitions = {}
            continue
        stripped = line.strip()
        d = re.match(r"^([plyV][₀-₉,]+) = (.*)$", stripped)
        if d:
            definitions[d.group(1)] = (len(d.group(2)), set(re.findall(r"[plyV][₀-₉,]+", d.group(2))))
            continue
        m = re.match(r"^(?:where\s+)?(S[₀-₉]+) = (.*?)(?: \(.*\))?$", stripped)
        if m:
            named[m.group(1)] = len(m.group(2))
            continue
        if not stripped.startswith(("superball", "contact", "M positive", "asymptotic:")):
            continue
        if not stripped.startswith("asymptotic:"):
            title = stripped
            continue
        if skip_psd and title.startswith("M positive"):
            continue
        formula = stripped[len("asymptotic:"):].strip()
        formula = re.sub(r"\s*\[[^\]]*\]$", "", formula)
        size = len(formula) + sum(n for name, n in named.items() if re.search(re.escape(name) + r"(?![₀-₉])", formula))
        sizes.append(size)
        seen, todo = set(), [n for n in re.findall(r"[plyV][₀-₉,]+", formula) if n in definitions]
        while todo:
            name = todo.pop()
            if name in seen:
                continue
            seen.add(name)
            todo.extend(n for n in definitions[name][1] if n in definitions)
        closures.append(size + sum(definitions[n][0] + len(n) + 3 for n in seen))
    if not sizes:
        print("readability.py: no asymptotic line in " + args[0], file=sys.stderr)
        return 1
    sizes.sort()
    k = len(sizes)
    p90 = sizes[min(k - 1, int(0.9 * k))]
    print(f"asymptotic conditions: {k}, median {sizes[k // 2]}, 90th percentile {p90}, longest {sizes[-1]} characters")
    closures.sort()
    print(f"with the elimination definitions they depend on: median {closures[k // 2]}, "
          f"90th percentile {closures[min(k - 1, int(0.9 * k))]}, longest {closures[-1]} characters")
    print(f"longest line of the output: {max(len(l) for l in lines)} characters")
    return 0


if __name__ == "__main__":
    sys.exit(main())
