#!/usr/bin/env bash
# Installs what motiongraph needs on Debian 12 (bookworm), in two sets:
#   --demo   what scripts/demo.sh needs: compilers, CMake/Ninja, the -dev packages the program is
#            built with, gnuplot (eval's plots), Node.js/npm and the studio's npm packages (web/).
#   (none)   all of that, plus what scripts/test.sh needs: GoogleTest, Google Benchmark, clang
#            with its sanitizer/fuzzer runtime, numpy, Blender (a test imports our BVH into it),
#            chromium and curl (the studio's browser and socket tests), the tests' npm packages,
#            pybind11, numpy, pytest and venv (the Python package and its tests; a build without
#            pybind11 simply leaves the package out), and Open MPI (`mpirun -np N motiongraph
#            build`, docs/cluster.md, and its test; a build without it runs on one process).
# Node.js is Debian 12's own (18.x); the npm lockfiles pin versions that run on it, and npm is
# told to refuse any package whose "engines" excludes the Node.js at hand (--engine-strict).
# Run as root, or as a user with sudo. Safe to run again: it skips what is present.
set -euo pipefail

mode=test
case "${1:-}" in
  --demo) mode=demo ;;
  "") ;;
  *) echo "usage: scripts/install-deps.sh [--demo]" >&2; exit 2 ;;
esac

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libopenblas-dev
  libcli11-dev nlohmann-json3-dev libspdlog-dev libfmt-dev libtomlplusplus-dev
  libstb-dev zlib1g-dev libcpp-httplib-dev libtinygltf-dev libassimp-dev
  gnuplot-nox
)
if [ "$mode" = test ]; then
  packages+=(
    clang libclang-rt-14-dev llvm
    libgtest-dev libgmock-dev libbenchmark-dev
    python3-numpy blender chromium curl
    python3-dev python3-pybind11 python3-pytest python3-venv
    libopenmpi-dev openmpi-bin
  )
fi
# Node.js may come from elsewhere than Debian (its own packages conflict with Debian's npm).
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then packages+=(nodejs npm); fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]})); then
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
  echo "installing: ${missing[*]}"
  "${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
  "${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# The versions the rest relies on, checked before anything is built: one line if one is wrong.
node_version=$(node --version 2>/dev/null || true)
node_major=${node_version#v}
node_major=${node_major%%.*}
if ! [[ "$node_major" =~ ^[0-9]+$ ]] || ((node_major < 18)); then
  echo "install-deps: Node.js ${node_version:-(none)} is too old: the studio and the tests need 18 or newer" \
       "(Debian 12's nodejs package is 18.x)" >&2
  exit 1
fi

# Node packages pinned by their lockfiles: the studio's front-end (three.js, served by
# `motiongraph serve`) and, for the tests, three.js's BVHLoader and playwright-core.
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
npm_dirs=(web)
if [ "$mode" = test ]; then npm_dirs+=(tests/js); fi
for dir in "${npm_dirs[@]}"; do
  if ! (cd "$here/$dir" && npm ci --engine-strict --no-audit --no-fund --loglevel=error); then
    echo "install-deps: npm ci failed in $dir (with Node.js $node_version): see npm's message above" >&2
    exit 1
  fi
done
