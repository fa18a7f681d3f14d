"""Builds the extension lightcone._lightcone with the project's CMake (pyproject.toml says
why setuptools). LIGHTCONE_BUILD_DIR names a CMake build folder to build in (and reuse);
otherwise setuptools' temporary folder is used."""

import os
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        source = os.path.dirname(os.path.abspath(__file__))
        build = os.environ.get("LIGHTCONE_BUILD_DIR") or os.path.join(self.build_temp, "cmake")
        # A build folder already configured keeps its Python (a virtual environment's is the
        # same interpreter as the one it was made from).
        configure = ["cmake", "-S", source, "-B", build]
        if not os.path.exists(os.path.join(build, "CMakeCache.txt")):
            configure += ["-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                          f"-DPython3_EXECUTABLE={sys.executable}"]
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", build, "--target", "_lightcone"], check=True)
        built = os.path.join(build, "python", "lightcone", os.path.basename(self.get_ext_fullpath(ext.name)))
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built, target)
        # The star catalogue (scenes with "stars"), in the package's data/ folder.
        catalogue = os.path.join(build, "data", "stars-bright.lcstars")
        if os.path.exists(catalogue):
            os.makedirs(os.path.join(os.path.dirname(target), "data"), exist_ok=True)
            shutil.copyfile(catalogue, os.path.join(os.path.dirname(target), "data",
                                                    os.path.basename(catalogue)))


setup(
    packages=["lightcone"],
    package_dir={"": "python"},
    package_data={"lightcone": ["py.typed", "_lightcone.pyi"]},
    ext_modules=[Extension("lightcone._lightcone", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": "build/setuptools"}, "egg_info": {"egg_base": "build"}},
)
