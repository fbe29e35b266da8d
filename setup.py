"""Installs the Python package ``phedra`` (docs/python.md):

    python3 -m venv --system-site-packages venv
    venv/bin/pip install .

Its compiled core is built with the project's CMake build (scripts/setup.sh
installs what it needs): in ``build/`` beside this file, or in the folder named
by PHEDRA_BUILD_DIR; an existing build is reused. Needs only Debian's pip,
setuptools, pybind11 and numpy (no package index is asked: there is no
pyproject.toml, so pip builds with the setuptools it has).
"""

import glob
import os
import re
import shutil
import subprocess

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


def version():
    with open(os.path.join(ROOT, "CMakeLists.txt"), encoding="utf-8") as f:
        return re.search(r"project\(phedra VERSION ([0-9.]+)", f.read()).group(1)


class CMakeBuild(build_ext):
    """Builds the module phedra._core with CMake and copies it into the package."""

    def build_extension(self, ext):
        build = os.environ.get("PHEDRA_BUILD_DIR", os.path.join(ROOT, "build"))
        if not os.path.exists(os.path.join(build, "CMakeCache.txt")):
            subprocess.check_call(["cmake", "-S", ROOT, "-B", build, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                                   "-DCMAKE_UNITY_BUILD=ON"])
        subprocess.check_call(["cmake", "--build", build, "--target", "phedra_python", "--parallel",
                               str(os.cpu_count() or 1)])
        built = glob.glob(os.path.join(build, "python", "phedra", "_core*.so"))
        if len(built) != 1:
            raise RuntimeError(f"phedra: the build left {len(built)} modules _core*.so in {build}/python/phedra")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built[0], target)


# setuptools' own files under the CMake build's folder, not beside the sources.
SETUPTOOLS_BASE = os.path.join("build", "python-package")
os.makedirs(os.path.join(ROOT, SETUPTOOLS_BASE), exist_ok=True)

setup(
    name="phedra",
    version=version(),
    description="Rigid-foldable P-hedra: the exact folding motion, tubes, tube arrays, mechanics and exports",
    packages=["phedra", "phedra.atlas"],
    package_dir={"": "python"},
    ext_modules=[Extension("phedra._core", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    install_requires=["numpy"],
    extras_require={"atlas": ["scipy", "distributed", "zarr", "xarray", "matplotlib"]},
    python_requires=">=3.9",
    zip_safe=False,
    options={"build": {"build_base": SETUPTOOLS_BASE}, "egg_info": {"egg_base": SETUPTOOLS_BASE}},
)
