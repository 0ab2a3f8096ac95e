"""superball from Python in a few lines: a solve in exact rationals, a sweep
of 10^5 values, the switch points, a derived condition, an error.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/example.py [SCENE]

(no PYTHONPATH once the module is installed).  SCENE defaults to the
paper's §4.4 scene, cases/scenes/paper-4.4-alpha2.toml.
"""
import pathlib
import sys

import superball

default = pathlib.Path(__file__).resolve().parents[2] / "cases" / "scenes" / "paper-4.4-alpha2.toml"
scene = superball.Scene.load(sys.argv[1] if len(sys.argv) > 1 else default)
r = superball.solve(scene, "exact")
print(r)
print(r.velocities_after_exact[0])
s = superball.sweep(scene, "K.3-4", superball.linspace(0, 20, 100001))
print(s.velocities.shape, sorted(set(s.cases)))
for p in superball.switch_points(scene, "K.3-4", superball.linspace(0, 20, 401)):
    print(p.text, p.case_below, "->", p.case_above)
d = superball.derive(case="1", alphas=2)
c = d.condition("U1 > a")
print(c.text, "|", c.asymptotic_text, "|", c.to_sympy())
try:
    scene.with_value("g", -1)
except ValueError as e:
    print("ValueError:", e)
