"""Installs the neuv package with a copy of libneuv.so inside it.

The library is taken from $NEUV_LIBRARY, else from the repository's
build/libneuv.so (`make python` builds it and runs this through pip)."""
import os
import shutil

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

HERE = os.path.dirname(os.path.abspath(__file__))


class build_py_with_library(build_py):
    def run(self):
        super().run()
        lib = os.environ.get("NEUV_LIBRARY") or os.path.join(HERE, os.pardir, "build", "libneuv.so")
        if not os.path.exists(lib):
            raise SystemExit(f"neuv: {os.path.normpath(lib)} not found: build the library first "
                             "(`make python` does), or set NEUV_LIBRARY")
        target = os.path.join(self.build_lib, "neuv", "libneuv.so")
        self.mkpath(os.path.dirname(target))
        shutil.copyfile(os.path.realpath(lib), target)  # the file, not the symlink chain
        os.chmod(target, 0o755)


class BinaryDistribution(Distribution):
    """The package carries a shared library: a platform wheel, not a pure one."""

    def has_ext_modules(self):
        return True


setup(cmdclass={"build_py": build_py_with_library}, distclass=BinaryDistribution)
