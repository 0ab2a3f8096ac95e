"""examples/python/superball_tour.ipynb runs headless (nbclient) without an error."""
import os

import pytest

from conftest import SCENES, SOURCE_DIR

NOTEBOOK = SOURCE_DIR / "examples" / "python" / "superball_tour.ipynb"


def test_the_tour_runs():
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    nb = nbformat.read(NOTEBOOK, as_version=4)
    os.environ.setdefault("SUPERBALL_SCENES", str(SCENES))
    os.environ.pop("MPLBACKEND", None)  # the kernel's inline backend (Agg) puts the figures in the notebook
    os.environ.setdefault("PYDEVD_DISABLE_FILE_VALIDATION", "1")  # the kernel's debugger note on frozen modules
    client = nbclient.NotebookClient(nb, timeout=300, kernel_name="python3",
                                     resources={"metadata": {"path": str(NOTEBOOK.parent)}})
    client.execute()  # raises CellExecutionError on the first cell that fails
    outputs = [o for cell in nb.cells if cell.cell_type == "code" for o in cell.get("outputs", [])]
    assert not [o for o in outputs if o.get("output_type") == "error"]
    text = "".join(o.get("text", "") for o in outputs if o.get("output_type") == "stream")
    assert "case 2.2 -> 3.3" in text and "case 3.3 -> 3.2" in text
    assert "exact conditions agree at every point: True" in text
    assert "map of " in text and "superball (U1+ > a):" in text and "first boundary point: " in text
    assert sum("image/png" in o.get("data", {}) for o in outputs) >= 2, "the sweep's and the map's figures were not both drawn"
    assert any("text/latex" in o.get("data", {}) for o in outputs), "no condition was shown as LaTeX"


def test_the_example_script_prints_what_the_readme_shows():
    """examples/python/example.py (README, "Use from Python"): its output, checked
    against what the libraries say, not against a stored copy."""
    import subprocess
    import sys

    script = SOURCE_DIR / "examples" / "python" / "example.py"
    p = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=300, env=os.environ)
    assert p.returncode == 0, p.stderr
    lines = p.stdout.splitlines()
    assert lines[1] == "1425207149882365049811/430982092965922100000"  # eq. (16)'s U1+ exactly (docs/RESULTS.md)
    assert lines[2] == "(100001, 4) ['2.2', '3.2', '3.3']"
    assert [l.split()[1:] for l in lines[3:5]] == [["2.2", "->", "3.3"], ["3.3", "->", "3.2"]]
    assert lines[5].startswith("−α₂ > 2m₁ + K₁₂ + K₁₃ | −α₂ > K₁₂ + K₁₃ |")
    assert lines[6].startswith("ValueError: ") and "g: must be > 0 (got -1)" in lines[6]
