# Sourced by the large benchmarks (bench-large.sh, bench-cluster.sh): the motiongraph binary
# built in Release (in $BUILD_DIR, default build), and the large CMU set (cmu-large.tar.xz)
# unpacked once into it; sets `bin`, `work` (the folder of the runs) and `subjects` (the subject
# folders). Run from the project's root.
# Usage: source scripts/large-data.sh ARCHIVE
build=${BUILD_DIR:-build}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --target motiongraph
bin=$build/motiongraph
work=$build/cmu-large
if [[ ! -d $work/cmu-large ]]; then
  mkdir -p "$work"
  tar xJf "$1" -C "$work"
fi
subjects=("$work"/cmu-large/*/)
