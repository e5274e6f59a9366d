"""Builds the wrc Python module with the project's CMake for `pip install .` (pyproject.toml).

Only the module's target and what it links (the runtime) are built, for the interpreter that runs
pip; the version is the one CMakeLists.txt's project() declares.
"""
import os
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE = os.path.dirname(os.path.abspath(__file__))


def project_version():
    with open(os.path.join(SOURCE, "CMakeLists.txt"), encoding="utf-8") as cmake:
        match = re.search(r"project\(wrc VERSION ([0-9.]+)", cmake.read())
    if not match:
        raise RuntimeError("CMakeLists.txt declares no project(wrc VERSION ...)")
    return match.group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = os.path.abspath(os.path.join(self.build_temp, "cmake"))
        configure = [
            "cmake", "-S", SOURCE, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
            "-DWRC_BUILD_TESTS=OFF", "-DWRC_BUILD_BENCHMARKS=OFF", "-DWRC_BUILD_PYTHON=ON",
            f"-DPython3_EXECUTABLE={sys.executable}",
        ]
        subprocess.run(configure, check=True)
        jobs = str(os.cpu_count() or 1)
        subprocess.run(["cmake", "--build", build, "--target", "wrc_python", "-j", jobs], check=True)
        built = [f for f in os.listdir(os.path.join(build, "python")) if f.startswith("wrc.")]
        if len(built) != 1:
            raise RuntimeError(f"expected one wrc module in {build}/python, found {built}")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(os.path.join(build, "python", built[0]), target)


setup(
    version=project_version(),
    ext_modules=[Extension("wrc", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
)
