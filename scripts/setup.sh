#!/usr/bin/env bash
# Installs the Debian packages neuv needs. Non-interactive and idempotent:
# apt-get update runs only when something is missing. Root, or sudo otherwise.
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config
  libopenblas-dev liblapacke-dev     # dense products (cblas_sgemm), LAPACK
  libsuitesparse-dev                 # CHOLMOD sparse factorizations
  libarpack2-dev                     # generalized eigenpairs
  libassimp-dev                      # mesh formats (STL, glTF/GLB, ...)
  libpng-dev zlib1g-dev              # preview pictures
  libmeshoptimizer-dev               # simplification for large meshes
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev  # isotropic remeshing (header-only CGAL; GMP/MPFR for exact predicates)
  python3-scipy python3-numpy        # benchmarks (SciPy reference); NumPy for the Python package
  python3-pytest                     # the Python package's tests
  python3-venv python3-setuptools python3-wheel  # make python: a venv, built and installed without network
)
# Blender 3.4 for the add-on's headless test (tests/cli_blender.sh), which
# `make test` runs; it is large, so NEUV_NO_BLENDER=1 leaves it out (the test then skips).
if [ -z "${NEUV_NO_BLENDER:-}" ]; then PACKAGES+=(blender); fi

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else
    echo "setup: missing packages (${missing[*]}) and not root, no sudo" >&2; exit 1; fi
fi

echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
