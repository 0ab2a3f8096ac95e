"""The installed module: `python3 check_installed.py PREFIX PACKAGE_DIR SCENE`.

Imports superball from PACKAGE_DIR (under PREFIX) only, solves SCENE in
exact arithmetic and checks that every superball library the process
loaded comes from PREFIX (the extension's RPATH), not from a build tree.
Used by ctest (python_installed) and scripts/test.sh's install check.
"""
import os
import sys

prefix, package_dir, scene = (os.path.realpath(a) for a in sys.argv[1:4])
sys.path.insert(0, package_dir)
import superball  # noqa: E402

where = os.path.realpath(superball.__file__)
assert where.startswith(package_dir + os.sep), f"superball imported from {where}, not from {package_dir}"
r = superball.solve(superball.Scene.load(scene), "exact")
assert r.status == "success" and r.case == "3.3" and r.superball, r
loaded = set()
with open("/proc/self/maps") as maps:
    for line in maps:
        path = line.split()[-1]
        if "libsuperball" in path or "_superball" in path:
            loaded.add(os.path.realpath(path))
libs = sorted(loaded)
assert any("libsuperball_numeric" in p for p in libs), libs
outside = [p for p in libs if not p.startswith(prefix + os.sep)]
assert not outside, f"loaded from outside {prefix}: {outside}"
print(f"installed module {where}: {r.case} U1+ = {r.velocities_after_exact[0]}; {len(libs)} superball libraries, all from {prefix}")
