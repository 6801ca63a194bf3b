"""Shared fixtures of the Python tests (python/tests; ctest python.pytest, or
`PYTHONPATH=build/python /usr/bin/python3 -m pytest python/tests` from the source tree)."""
import ctypes
import glob
import os

import pytest

import railcontact


def shared_library_path():
    """The shared library librailcontact.so of the package under test, for its C API through
    ctypes: RAILCONTACT_LIBRARY when set, else found from the package's own location, in the
    build tree (BUILD/python/railcontact -> BUILD) or in an installed prefix
    (P/lib/python3.X/dist-packages/railcontact -> P/lib). None when there is none."""
    given = os.environ.get("RAILCONTACT_LIBRARY")
    if given:
        return given
    package = os.path.dirname(os.path.abspath(railcontact.__file__))
    for up in (2, 3):
        folder = os.path.normpath(os.path.join(package, *[".."] * up))
        found = sorted(glob.glob(os.path.join(folder, "librailcontact.so*")), key=len)
        if found:
            return found[0]
    return None


@pytest.fixture(scope="session")
def c_library():
    """The C API of librailcontact.so (ctypes.CDLL)."""
    path = shared_library_path()
    if path is None:
        pytest.skip(f"librailcontact.so is neither next to the package railcontact "
                    f"({os.path.dirname(railcontact.__file__)}, two or three folders up) nor given as "
                    "RAILCONTACT_LIBRARY: build the target railcontact_shared")
    return ctypes.CDLL(path)
