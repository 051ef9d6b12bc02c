#!/usr/bin/env bash
# Installs the Debian 12 (bookworm) packages growshell needs, and only those that are missing:
# a machine that already has everything needs neither root nor network.
set -euo pipefail

packages=(
  build-essential      # C++20 compiler (GCC 12), make, dpkg-dev
  cmake                # build system (>= 3.25)
  pkg-config           # locates Ipopt (ipopt.pc)
  libeigen3-dev        # dense/sparse linear algebra at every interface (public dependency)
  libsuitesparse-dev   # CHOLMOD sparse Cholesky for the Newton solver
  libmetis-dev         # fill-reducing ordering used by CHOLMOD
  libopenblas-dev      # optimised BLAS/LAPACK behind CHOLMOD's supernodal factorisation
  coinor-libipopt-dev  # interior-point optimiser for the contact layer
  libmumps-seq-dev     # sequential MUMPS: symmetric indefinite LDL^T with inertia (stability)
  nlohmann-json3-dev   # JSON parameter and result files
  gmsh libgmsh-dev     # well-kept unstructured mesh generator: the second disc mesh family, sharing no structure with the ring mesh
  libgtest-dev         # unit tests
  clang libclang-rt-14-dev  # libFuzzer and the sanitizers' runtimes: scripts/run_sanitizers.sh (fuzz preset)
  libbenchmark-dev     # micro-benchmarks
  libopenmpi-dev openmpi-bin  # mpirun -n K growshell sweep: the sweep's points spread over MPI ranks (programs/ only)
  python3-matplotlib   # figures: scripts/plot_study.py (growshell run draws DIR/eb_hat.png), render_surface.py
  python3              # the layering test (tests/layering/check_layering.py)
  python3-dev python3-pybind11  # the Python module `growshell` (python/), built against Debian's python3
  python3-numpy python3-scipy   # the module's arrays (numpy) and sparse Hessians (scipy.sparse)
  python3-pytest       # the module's tests (tests/python/), run by ctest
)

missing=()
for p in "${packages[@]}"; do
  # Status "installed" only; "config-files" (removed, not purged) counts as missing.
  if [[ "$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)" != installed ]]; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} > 0)); then
  echo "setup_debian.sh: installing ${missing[*]}"
  if [[ $(id -u) -eq 0 ]]; then
    as_root=()
  elif command -v sudo >/dev/null 2>&1; then
    as_root=(sudo)
  else
    echo "setup_debian.sh: need root (or sudo) to install: ${missing[*]}" >&2
    exit 1
  fi
  # `env` passes DEBIAN_FRONTEND through sudo's environment reset.
  "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
  "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive \
    apt-get install -y -q --no-install-recommends "${missing[@]}"
else
  echo "setup_debian.sh: all ${#packages[@]} packages already installed"
fi

# CHOLMOD's supernodal factorisation spends its time in BLAS; with OpenBLAS it was measured at
# 1.4 s against 3.5 s with the reference BLAS at 61k unknowns. Installing libopenblas-dev
# registers OpenBLAS with the libblas.so.3 alternative at a higher priority than the reference
# BLAS, so in the default "auto" mode the alternative points to OpenBLAS. Someone may have
# pinned it manually, so check rather than assume; only warn, as it is a machine-wide setting.
multiarch="$(dpkg-architecture -qDEB_HOST_MULTIARCH 2>/dev/null || gcc -print-multiarch)"
blas="$(update-alternatives --query "libblas.so.3-${multiarch}" 2>/dev/null |
        sed -n 's/^Value: //p' || true)"
if [[ "$blas" == *openblas* ]]; then
  echo "setup_debian.sh: BLAS is OpenBLAS ($blas)"
else
  echo "setup_debian.sh: WARNING: libblas.so.3 points to '${blas:-nothing}', not OpenBLAS;" \
       "CHOLMOD will be ~2.5x slower. Fix with: update-alternatives --auto libblas.so.3-${multiarch}" >&2
fi
