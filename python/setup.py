"""Builds mosb._mosb against the repository's own library, as CMake builds it.

The extension links the static libraries of the components it binds (lib/core, lib/pack,
lib/store, lib/solutions), which this script has CMake build first from ../CMakeLists.txt: the same targets, the
same sources and flags the `mosb` program is built from, so validation and error messages are
identical, and there is no second list of the library's sources to keep in step. It needs this
checkout, CMake, a C++20 compiler, pybind11 and the components' libraries (libxxhash, libzstd,
libcrypto, nlohmann-json headers): no prior `cmake --install`, no library search path at run time,
and no chance of binding a different version of the reader than the one in this tree.
"""
import os
import re
import shutil
import subprocess

from pybind11.setup_helpers import Pybind11Extension, build_ext
from setuptools import setup
from setuptools.command.build_py import build_py

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(here)
# The components the binding uses, in link order: each before the components it depends on.
COMPONENTS = ("store", "solutions", "pack", "core")


def project_version():
    # The one version number: project(mosb VERSION x.y.z) in the top-level CMakeLists.txt.
    try:
        with open(os.path.join(root, "CMakeLists.txt"), encoding="utf-8") as f:
            match = re.search(r"project\(\s*mosb\s+VERSION\s+([0-9.]+)", f.read())
    except OSError:
        match = None
    if not match:
        raise SystemExit("mosb: python/ must be built from inside the mosb repository "
                         "(no project(mosb VERSION ...) in ../CMakeLists.txt)")
    return match.group(1)


class BuildWithCMake(build_ext):
    """Builds the components with CMake, then the extension linked against them."""

    def run(self):
        cmake = shutil.which("cmake")
        if not cmake:
            raise SystemExit("mosb: building the Python package needs cmake (Debian: cmake)")
        build = os.path.join(here, "build", "cmake")
        # Two jobs: the build machines are shared (see README); NPY_NUM_BUILD_JOBS overrides.
        jobs = os.environ.get("NPY_NUM_BUILD_JOBS", "2")
        subprocess.run([cmake, "-S", root, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                        "-DBUILD_SHARED_LIBS=OFF", "-DMOSB_BUILD_TOOLS=OFF",
                        "-DMOSB_BUILD_TESTS=OFF", "-DMOSB_BENCHMARKS=OFF",
                        "-DMOSB_BUILD_EXAMPLES=OFF", "-DMOSB_INSTALL=OFF"], check=True)
        subprocess.run([cmake, "--build", build, "-j", jobs, "--target"] +
                       ["mosb_" + c for c in COMPONENTS], check=True)
        archives = [os.path.join(build, "lib", c, "libmosb_%s.a" % c) for c in COMPONENTS]
        for ext in self.extensions:
            ext.include_dirs += [os.path.join(root, "lib", c, "include") for c in COMPONENTS]
            ext.include_dirs += [os.path.join(root, "format", "include"),
                                 os.path.join(root, "lib", "core", "internal"),  # utf8.hpp
                                 os.path.join(build, "lib", "include")]  # version.hpp
            ext.extra_objects += archives
            # setuptools relinks when one of these is newer than the extension.
            ext.depends += archives
        super().run()


class BuildPyWithSuite(build_py):
    """Installs spec/suite.json, the suite's one description (the library compiles in the same
    file), as mosb/suite.json: mosb.suite() reads it."""

    def run(self):
        super().run()
        self.copy_file(os.path.join(root, "spec", "suite.json"),
                       os.path.join(self.build_lib, "mosb", "suite.json"))


extension = Pybind11Extension(
    "mosb._mosb",
    ["src/mosb_module.cpp"],
    libraries=["xxhash", "crypto", "zstd"],
    cxx_std=20,
)

setup(version=project_version(), ext_modules=[extension],
      cmdclass={"build_ext": BuildWithCMake, "build_py": BuildPyWithSuite})
