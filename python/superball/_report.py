"""The base of the results that are a command's report: ``str()`` is the command's text, ``to_dict()`` its
``--json`` and a notebook shows the text."""

from __future__ import annotations

import html as _html
from typing import Any, Dict


class _Report:
    def __init__(self, d: Dict[str, Any]) -> None:
        self._dict = {k: v for k, v in d.items() if k != "text"}
        self._text: str = d["text"]

    def to_dict(self) -> Dict[str, Any]:
        """The fields of the command's ``--json``."""
        return dict(self._dict)

    def __str__(self) -> str:
        return self._text

    def _repr_html_(self) -> str:
        return f"<pre>{_html.escape(self._text)}</pre>"
