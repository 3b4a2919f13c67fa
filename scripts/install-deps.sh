#!/usr/bin/env bash
# Installs what motiongraph needs on Debian 12 (bookworm): compilers, CMake/Ninja and the
# -dev packages found by find_package, gnuplot (eval's plots), Blender (a test imports our BVH
# into it), chromium (the studio's browser test), then the npm packages of the test tools and
# of the studio's front-end.
# Run as root, or as a user with sudo. Safe to run again: it skips what is present.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  clang libclang-rt-14-dev llvm
  libeigen3-dev libopenblas-dev
  libcli11-dev nlohmann-json3-dev libspdlog-dev libfmt-dev libtomlplusplus-dev
  libstb-dev libgtest-dev libgmock-dev libbenchmark-dev zlib1g-dev
  python3-numpy
  gnuplot-nox
  blender
  libcpp-httplib-dev chromium curl
)
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

# Node packages pinned by their lockfiles: the tests' (three.js's BVHLoader, playwright-core)
# and the studio's front-end (three.js, served by `motiongraph serve`).
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
for dir in tests/js web; do
  if [ -f "$here/$dir/package-lock.json" ]; then
    (cd "$here/$dir" && npm ci --no-audit --no-fund --loglevel=error)
  fi
done
