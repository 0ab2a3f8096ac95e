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
    assert any("image/png" in o.get("data", {}) for o in outputs), "the sweep's figure was not drawn"
    assert any("text/latex" in o.get("data", {}) for o in outputs), "no condition was shown as LaTeX"
