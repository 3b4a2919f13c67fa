#!/usr/bin/env bash
# The package installed for a user's Python: into a fresh virtual environment (seeing the
# system's numpy) with `cmake --install --component python`, then imported from elsewhere than
# the build tree and used.
# Usage: install_test.sh PYTHON CMAKE BUILD_DIR DATA_DIR
set -euo pipefail
python=$1 cmake=$2 build=$3 data=$4
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$python" -m venv --system-site-packages "$work/venv"
"$cmake" --install "$build" --component python --prefix "$work/venv" >/dev/null
cd "$work"
env -u PYTHONPATH "$work/venv/bin/python" - "$data" <<'PY'
import sys

import motiongraph as mg

assert mg.__file__.startswith(sys.prefix), mg.__file__
clip = mg.load_clip(sys.argv[1] + "/cmu/16/16_15.amc")
assert clip.positions.shape == (len(clip), len(clip.joint_names), 3), clip.positions.shape
print("installed:", mg.__file__, clip)
PY
