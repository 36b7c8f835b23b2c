"""pytest setup: import the package from this tree (python/) unless
PYTHONPATH already points elsewhere, and give the repository's paths."""
import os
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
if not any(os.path.isfile(os.path.join(p, "shlab", "__init__.py")) for p in sys.path if p):
    sys.path.insert(0, os.path.join(ROOT, "python"))


@pytest.fixture(scope="session")
def root():
    return ROOT


@pytest.fixture(scope="session")
def build():
    """The build directory (SHLAB_BUILD from make check, else build/)."""
    b = os.environ.get("SHLAB_BUILD", "build")
    return b if os.path.isabs(b) else os.path.join(ROOT, b)
