#!/usr/bin/env bash
# Installs shudder's dependencies from Debian 12 packages only. Safe to run again: packages
# already present are skipped. Needs root (or sudo).
#   bash scripts/install-deps.sh cli   what the `shudder` executable needs to build (run-default.sh)
#   bash scripts/install-deps.sh       everything: also tests, benchmarks, Python, MPI, FMU, fuzzing, plots
set -euo pipefail
cli_packages=(
  g++ cmake make ninja-build pkg-config  # ninja-build: the libraries compile side by side
  libeigen3-dev          # dense/sparse linear algebra (thermal solver, modal analysis)
  libboost-dev           # Boost.Odeint (header-only) for time integration
  libfftw3-dev           # spectra
  libhdf5-dev            # HDF5 output (C API)
  libtomlplusplus-dev    # TOML scenario parsing (toml++ 3.3, header-only, reports line/column)
  libcli11-dev           # command line parsing (CLI11, header-only)
)
rest_packages=(
  libgtest-dev libgmock-dev  # unit tests
  libbenchmark-dev       # benchmarks
  gnuplot-nox            # plots (PNG/SVG), driven by the program
  chromium               # the report tests load index.html headless and fail on a missing image or script error
  clang-format           # the C/C++ layout check of the test command (scripts/check-format.sh, .clang-format)
  clang                  # libFuzzer harnesses (fuzz/, scripts/sanitize.sh): -fsanitize=fuzzer is clang-only
  libclang-rt-14-dev     # clang 14's runtimes: libFuzzer, ASan and UBSan (libfuzzer-14-dev is not needed)
  pybind11-dev python3-dev  # the Python module (python/; docs/python.md), for Debian's /usr/bin/python3
  python3-numpy          # the Python module's signals are numpy arrays
  python3-pytest         # the Python module's tests (ctest python_module)
  python3-h5py           # docs/python.md reads the HDF5 outputs with it; the MPI sweep test compares files
  python3-matplotlib     # docs/python.md's worked example plots with it (run by the tests)
  libopenmpi-dev openmpi-bin  # `shudder sweep --mpi` across MPI ranks (docs/mpi.md; mpirun in the tests)
  libexpat1-dev          # the FMU test parses modelDescription.xml (tests/fmu)
  g++-mingw-w64-x86-64-posix  # the FMU's win64 binary, cross-built (docs/fmu.md "Platforms")
  wine64                 # the FMU test runs the win64 binary under Wine (tests/fmu)
)
case "${1:-all}" in
  cli) packages=("${cli_packages[@]}") ;;
  all) packages=("${cli_packages[@]}" "${rest_packages[@]}") ;;
  *) echo "install-deps: error: unknown set '$1'; use 'cli' or nothing (everything)" >&2; exit 2 ;;
esac
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
