"""Builds mosb._mosb from the repository's own reader sources (../lib, ../format).

Compiling the library sources into the extension, rather than linking an installed libmosb, needs
nothing but this checkout, a C++20 compiler, pybind11, libxxhash, libzstd, libcrypto (OpenSSL, for
the store's SHA-256) and the nlohmann-json headers: no prior `cmake --install`,
no library search path at run time, and no chance of binding a different version of the reader
than the one in this tree. The sources are the same files the CLI is built from, so validation and
error messages are identical.
"""
import glob
import os
import re

from pybind11.setup_helpers import ParallelCompile, Pybind11Extension
from setuptools import setup

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(here)


def relative(path):
    # setuptools wants source paths relative to setup.py.
    return os.path.relpath(path, here)


def library_sources():
    sources = sorted(glob.glob(os.path.join(root, "lib", "src", "*.cpp")) +
                     glob.glob(os.path.join(root, "format", "src", "*.cpp")))
    if not sources:
        raise SystemExit("mosb: python/ must be built from inside the mosb repository "
                         "(../lib/src and ../format/src not found)")
    return [relative(s) for s in sources]


def project_version():
    # The one version number: project(mosb VERSION x.y.z) in the top-level CMakeLists.txt.
    with open(os.path.join(root, "CMakeLists.txt"), encoding="utf-8") as f:
        match = re.search(r"project\(\s*mosb\s+VERSION\s+([0-9.]+)", f.read())
    if not match:
        raise SystemExit("mosb: no project(mosb VERSION ...) in ../CMakeLists.txt")
    return match.group(1)


def generated_include_dir(version):
    """Headers CMake generates with configure_file (lib/*.hpp.in -> include/mosb/*.hpp), made
    here the same way, from the same templates and the same version."""
    out = os.path.join(here, "build", "generated")
    major, minor, patch = (version.split(".") + ["0", "0"])[:3]
    values = {"PROJECT_VERSION": version, "PROJECT_VERSION_MAJOR": major,
              "PROJECT_VERSION_MINOR": minor, "PROJECT_VERSION_PATCH": patch}
    for template in sorted(glob.glob(os.path.join(root, "lib", "*.hpp.in"))):
        with open(template, encoding="utf-8") as f:
            text = re.sub(r"@([A-Za-z_]+)@", lambda m: values[m.group(1)], f.read())
        target = os.path.join(out, "mosb", os.path.basename(template)[:-len(".in")])
        os.makedirs(os.path.dirname(target), exist_ok=True)
        with open(target, "w", encoding="utf-8") as f:
            f.write(text)
    return out


version = project_version()

# Two jobs: the build machines are shared (see README); NPY_NUM_BUILD_JOBS overrides.
ParallelCompile("NPY_NUM_BUILD_JOBS", default=2).install()

extension = Pybind11Extension(
    "mosb._mosb",
    [relative(os.path.join(here, "src", "mosb_module.cpp"))] + library_sources(),
    include_dirs=[generated_include_dir(version), os.path.join(root, "lib", "include"),
                  os.path.join(root, "format", "include"), os.path.join(root, "lib", "src")],
    # Headers and templates too: setuptools rebuilds the extension only when one of these (or a
    # source) is newer than it.
    depends=[relative(h) for pattern in ("lib/include/*.h", "lib/include/mosb/*.hpp",
                                         "format/include/mosb/*.hpp", "lib/src/*.hpp",
                                         "lib/*.hpp.in", "CMakeLists.txt")
             for h in sorted(glob.glob(os.path.join(root, pattern)))],
    libraries=["xxhash", "crypto", "zstd"],
    cxx_std=20,
)

setup(version=version, ext_modules=[extension])
