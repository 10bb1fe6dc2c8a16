import os
import shutil

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, os.pardir, os.pardir))


@pytest.fixture(scope="session")
def cli():
    """The neuv command: $NEUV_CLI, else the repository's build/neuv."""
    path = os.environ.get("NEUV_CLI") or os.path.join(REPO, "build", "neuv")
    if not (os.path.isfile(path) and os.access(path, os.X_OK)):
        path = shutil.which("neuv")
    if not path:
        pytest.skip("no neuv command (set NEUV_CLI)")
    return path


@pytest.fixture(scope="session")
def header():
    """include/neuv/neuv.h of the repository the package sits in."""
    path = os.path.join(REPO, "include", "neuv", "neuv.h")
    if not os.path.exists(path):
        pytest.skip("no include/neuv/neuv.h beside the package")
    return path
