"""setup.py - the one step pyproject.toml cannot say: generate the
protocol's message types (package `mpb`) from the repository's
lcmtypes/*.lcm with lcm-gen (the `lcm` package's, a build requirement, or
Debian's on PATH) into the built package, so that an installed kit needs
no build tree."""
import glob
import os
import shutil
import subprocess
import sys

from setuptools import setup
from setuptools.command.build_py import build_py

HERE = os.path.dirname(os.path.abspath(__file__))
LCMTYPES = os.path.join(HERE, "..", "..", "lcmtypes")


def _lcm_gen():
    beside = os.path.join(os.path.dirname(sys.executable), "lcm-gen")
    found = beside if os.access(beside, os.X_OK) else shutil.which("lcm-gen")
    if not found:
        sys.exit("mpbplanner: no lcm-gen (pip install lcm, or Debian's "
                 "liblcm-bin) to generate the message types")
    return found


class BuildWithTypes(build_py):
    def run(self):
        super().run()
        files = sorted(glob.glob(os.path.join(LCMTYPES, "*.lcm")))
        if not files:
            sys.exit(f"mpbplanner: no .lcm files in {LCMTYPES}: build the "
                     "package from an mpbench checkout")
        subprocess.check_call([_lcm_gen(), "-p", "--ppath", self.build_lib]
                              + files)


setup(cmdclass={"build_py": BuildWithTypes})
