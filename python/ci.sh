#!/usr/bin/env bash
# The Python module's CI: bash python/ci.sh BUILD_DIR CLI_PATH, from the repository's root.
#
# Installs Debian's pybind11-dev, python3-numpy, python3-pytest and python3-dev if any is missing
# (as root; apt-get update only if the install fails without it), configures BUILD_DIR with
# -DNMESH_BUILD_PYTHON=ON -DNMESH_WERROR=ON (nothing else: no tests, tools, examples or
# benchmarks), builds, installs the package into BUILD_DIR/install, and runs the pytest suite
# against that installation, with CLI_PATH (the command-line tool of a build with the same
# compiler and build type, e.g. build/nmesh) for the byte-for-byte comparisons.
# Exits non-zero if any step or test fails. JOBS sets the build's parallel jobs (default 2).
set -euo pipefail

if [ $# -ne 2 ]; then
  echo "usage: bash python/ci.sh BUILD_DIR CLI_PATH" >&2
  exit 2
fi
# Absolute paths, resolved before moving to the repository's root.
build=$(realpath -m -- "$1")
cli=$(realpath -m -- "$2")
cd "$(dirname "$0")/.."
if [ ! -x "$cli" ]; then
  echo "python/ci.sh: $2 is not an executable (the nmesh command-line tool)" >&2
  exit 1
fi

echo "== Python module: Debian packages"
. .ci/debian_packages.sh
require_debian_packages python/ci.sh pybind11-dev python3-numpy python3-pytest python3-dev

echo "== Python module: configure, build, install into $build/install"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DNMESH_BUILD_PYTHON=ON -DNMESH_WERROR=ON \
  -DNMESH_BUILD_TESTS=OFF -DNMESH_BUILD_TOOLS=OFF -DNMESH_BUILD_EXAMPLES=OFF -DNMESH_BUILD_BENCH=OFF > /dev/null
cmake --build "$build" -j "${JOBS:-2}" --target nmesh_python
rm -rf "$build/install"
cmake --install "$build" --component python --prefix "$build/install" > /dev/null

# The interpreter the module was built for (CMake's Python3_EXECUTABLE: Debian's /usr/bin/python3).
python=$(sed -n 's/^Python3_EXECUTABLE:[A-Z]*=//p' "$build/CMakeCache.txt")
site="$build/install/$(sed -n 's/^NMESH_PYTHON_INSTALL_DIR:[A-Z]*=//p' "$build/CMakeCache.txt")"
echo "== Python module: pytest ($python, PYTHONPATH=$site, NMESH_CLI=$cli)"
# No .pyc files or pytest cache in the source tree.
PYTHONPATH="$site" NMESH_CLI="$cli" PYTHONDONTWRITEBYTECODE=1 \
  "$python" -m pytest -p no:cacheprovider -ra -q python/tests
