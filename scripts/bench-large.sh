#!/usr/bin/env bash
# Whole-library runs on the large CMU set (cmu-large.tar.xz: 262 k frames, 8 subjects), as
# recorded in docs/performance.md: `motiongraph build` at 30 and at 120 fps, with wall time and
# peak memory. The archive is not bundled: it is looked for at ../shared/data/ beside the
# project (or at the path given as the first argument); without it, this says so and stops.
# Usage: scripts/bench-large.sh [ARCHIVE] [FPS...]      (default FPS: 30 120)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
archive=${1:-../shared/data/cmu-large.tar.xz}
shift || true
rates=("$@")
((${#rates[@]})) || rates=(30 120)
if [[ ! -f $archive ]]; then
  echo "skipping the large benchmark: $archive not found (see docs/performance.md)"
  exit 0
fi
source scripts/large-data.sh "$archive"
for fps in "${rates[@]}"; do
  echo "== ${#subjects[@]} subjects at $fps fps"
  /usr/bin/time -f "wall %e s, peak memory %M KB" "$bin" build "${subjects[@]}" --fps "$fps" \
    -o "$work/large-$fps.mgraph" --no-cache --cmu-index data/cmu/cmu-mocap-index.tsv --report "$work/large-$fps.json"
  python3 -c "import json,sys; r=json.load(open(sys.argv[1])); print('timings (s):', {k: round(v, 1) for k, v in r['timings'].items()}); print('counts:', r['counts'])" "$work/large-$fps.json"
done
