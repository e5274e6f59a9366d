#!/usr/bin/env python3
"""`pip install .` as a Python user runs it: a copy of the project's files (git's, when SOURCE is a
checkout), a fresh venv with the system's packages visible (Debian's numpy), pip with
--no-build-isolation (no download), then from another directory: import wrc, check
wrc.__version__ and a lookup on TABLE (tests/integration/consumer/expected.h's value).

usage: pip_install_test.py SOURCE TABLE VERSION
"""
import os
import shutil
import subprocess
import sys
import tempfile

# The files of a user's copy, as the documented-commands test makes it.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "docs"))
from documented_commands import copy_project  # noqa: E402


def run(command, cwd):
    result = subprocess.run(command, cwd=cwd, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"failed ({result.returncode}): {' '.join(command)}\n{result.stdout}\n{result.stderr}")
    return result.stdout


def main():
    source, table, version = sys.argv[1:4]
    work = tempfile.mkdtemp(prefix="wrc-pip-")
    try:
        project = os.path.join(work, "wrc")
        copy_project(source, project)
        venv = os.path.join(work, "venv")
        run([sys.executable, "-m", "venv", "--system-site-packages", venv], work)
        python = os.path.join(venv, "bin", "python")
        run([python, "-m", "pip", "install", "--no-build-isolation", "--no-index", "-q", "."], project)
        elsewhere = os.path.join(work, "elsewhere")
        os.mkdir(elsewhere)
        check = (
            "import sys, wrc\n"
            f"assert wrc.__version__ == {version!r}, wrc.__version__\n"
            f"assert wrc.__file__.startswith({venv!r}), wrc.__file__\n"
            f"fx = wrc.Table({os.path.abspath(table)!r}).eval([0.5, 0.005])[0, 0]\n"
            "assert abs(fx - 3.625) <= 1e-12, fx\n"
            "print('pip-installed wrc', wrc.__version__, 'at', wrc.__file__, 'fx =', fx)\n"
        )
        print(run([python, "-c", check], elsewhere), end="")
    finally:
        shutil.rmtree(work, ignore_errors=True)


main()
