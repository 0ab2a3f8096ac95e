"""The Python module's reference: every public name of ``superball`` must have
a docstring, and the module's pydoc HTML is written to the folder given.

    python3 docs/api/python_docs.py OUTPUT_FOLDER   (superball importable)

Public names are those of ``superball.__all__`` and, for each class among
them, every attribute defined in the class whose name does not start with an
underscore (methods, properties, class and static methods).  Constants carry
no docstring of their own; pydoc shows their values.  Exit status 1, with one
line per name missing a docstring, when any is missing.
"""

import inspect
import os
import pydoc
import sys

import superball


def _documented(obj) -> bool:
    doc = inspect.getdoc(obj)
    return bool(doc and doc.strip())


def missing_docstrings(module) -> list:
    """The public names of ``module`` (``__all__``) without a docstring, as 'module.Name[.member]'."""
    missing = []
    if not _documented(module):
        missing.append(module.__name__)
    for name in module.__all__:
        obj = getattr(module, name)
        if not (inspect.isclass(obj) or inspect.isroutine(obj)):
            continue  # a constant
        if not _documented(obj):
            missing.append(f"{module.__name__}.{name}")
        if not inspect.isclass(obj):
            continue
        for member, value in vars(obj).items():
            if member.startswith("_"):
                continue
            if isinstance(value, (staticmethod, classmethod)):
                value = value.__func__
            if isinstance(value, property) or inspect.isroutine(value):
                # A property's docstring is its getter's; an inherited docstring counts.
                if not _documented(getattr(obj, member) if not isinstance(value, property) else value):
                    missing.append(f"{module.__name__}.{name}.{member}")
    return missing


def main(argv) -> int:
    if len(argv) != 2:
        print("usage: python_docs.py OUTPUT_FOLDER", file=sys.stderr)
        return 2
    missing = missing_docstrings(superball)
    for name in missing:
        print(f"python_docs: {name}: no docstring", file=sys.stderr)
    os.makedirs(argv[1], exist_ok=True)
    os.chdir(argv[1])
    pydoc.writedoc(superball)  # superball.html, beside the C++ reference
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
