#!/usr/bin/env bash
# The build of the large CMU set (cmu-large.tar.xz, 8 subjects) on one process and on MPI
# processes, as recorded in docs/cluster.md: wall time, the distance stage's time and per-pair
# rate, each process's peak memory, and the check that both runs make the same graph (the
# reports but for how they ran, and the nodes). Needs a build with MPI (mpirun). The archive is
# looked for at ../shared/data/ beside the project (or given); without it this says so and stops.
# BUILD_DIR=DIR: the build to use (default build; configured in Release).
# Usage: scripts/bench-cluster.sh [ARCHIVE] [FPS] [PROCESSES] [THREADS_PER_PROCESS]
#        (defaults: 30 fps, 2 processes of 1 thread: the two cores of the recorded machine)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
archive=${1:-../shared/data/cmu-large.tar.xz}
fps=${2:-30}
processes=${3:-2}
threads=${4:-1}
if [[ ! -f $archive ]]; then
  echo "skipping the cluster benchmark: $archive not found (see docs/cluster.md)"
  exit 0
fi
source scripts/large-data.sh "$archive"
common=("${subjects[@]}" --fps "$fps" --no-cache --cmu-index data/cmu/cmu-mocap-index.tsv -q)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
echo "== ${#subjects[@]} subjects at $fps fps: one process"
/usr/bin/time -f "wall %e s, cpu %U s user + %S s system, peak memory %M KB" "$bin" build "${common[@]}" \
  -o "$work/one-$fps.mgraph" --report "$work/one-$fps.json"
echo "== $processes processes of $threads thread(s)"
/usr/bin/time -f "wall %e s, cpu %U s user + %S s system (all processes)" mpirun -q --oversubscribe -np "$processes" "$bin" build \
  "${common[@]}" --threads "$threads" -o "$work/mpi-$fps.mgraph" --report "$work/mpi-$fps.json"
"$bin" inspect --nodes "$work/one-$fps.mgraph" >"$work/one-$fps.nodes"
"$bin" inspect --nodes "$work/mpi-$fps.mgraph" >"$work/mpi-$fps.nodes"
cmp "$work/one-$fps.nodes" "$work/mpi-$fps.nodes" && echo "same nodes"
python3 - "$work/one-$fps.json" "$work/mpi-$fps.json" <<'PY'
import json, sys
reports = [json.load(open(p)) for p in sys.argv[1:3]]
for r in reports:
    t = r["timings"]["distance"]
    print(f"{r['processes']} process(es): distance {t:.1f} s, {r['counts']['pairs'] / t / 1e6:.1f} M pairs/s, "
          f"each process's tiles (s): {[round(s, 1) for s in r['share_seconds']]}, "
          f"peak memory by process (MB, end of the distance stage): {[round(m) for m in r['peak_memory_mb']]}, "
          f"counts {r['counts']}")
    for key in ("timings", "processes", "peak_memory_mb", "share_seconds", "restored_tiles"):
        r.pop(key)
    for point in (r["path_check"] or {}).get("points", []):
        point.pop("seconds")
diff = [k for k in reports[0] if reports[0][k] != reports[1].get(k)]
print("same report" if not diff else f"the reports differ in {diff}")
sys.exit(1 if diff else 0)
PY
