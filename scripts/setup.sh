#!/usr/bin/env bash
# setup.sh — install what is missing (Debian 12 packages only), then configure and build pdd
# in Release into build/ (the Python module, for /usr/bin/python3, into build/python/). Safe to
# run again: installs nothing that is already there and rebuilds only what changed. Used by both
# README commands and by CI.
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(
  build-essential cmake pkg-config
  libcgal-dev libgmp-dev libmpfr-dev      # exact engine: CGAL kernels, hull, QP solver; GMP
  libeigen3-dev                           # tests of the fast engine (dense QP check)
  libtbb-dev                              # parallel batches
  nlohmann-json3-dev libcli11-dev         # JSON fixtures and output; command-line parsing
  libboost-test-dev                       # unit tests
  libfcl-dev libccd-dev                   # rigid-PD peers in pdd bench
  clang-14 libclang-rt-14-dev             # second compiler (sanitized build in CI), libFuzzer
  gnuplot-nox                             # pictures of pdd paper
  pybind11-dev python3-dev python3-numpy  # the Python module (python/), for /usr/bin/python3
  python3-pytest python3-distributed      # its tests; the dask example
  python3-meshio                          # its mesh tests: meshes read by meshio (test_mesh.py)
  python3-tqdm                            # its progress bars (progress=True)
  python3-scipy                           # pdd.contact_energy's Hessian (scipy.sparse), examples/soft_body.py
  python3-matplotlib                      # scripts/render-resolve.py (pictures of pdd resolve)
  gmsh                                    # scripts/make-meshes.sh, mesher-survey.py (meshes; GPL, never linked)
  tetgen                                  # scripts/make-resolve-cases.sh, mesher-survey.py (never linked)
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# Debian's interpreter, the one with numpy (the python3 first on PATH may be another one).
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE=/usr/bin/python3 >/dev/null
cmake --build build -j"$(nproc)"
