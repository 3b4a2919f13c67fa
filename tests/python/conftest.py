"""What the Python tests share: the CLI binary, the bundled data and the subject-16 graph.

CTest runs them (tests/CMakeLists.txt) with the package on PYTHONPATH and MOTIONGRAPH (the CLI),
MOTIONGRAPH_DATA (data/) and MOTIONGRAPH_TEST_GRAPH (the subject-16 graph the library makes,
the CTest fixture subject16_graph) in the environment, and MAKE_TEST_FBX (tests/cli/make_test_fbx,
for FBX input). Every comparison is with what the CLI
writes for the same input.
"""
import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import motiongraph as mg

# The report entries that are timings (and peak memory), which differ from run to run.
TIMING_KEYS = {"seconds", "realtime_factor", "search_seconds", "search_realtime_factor", "search_cpu_seconds",
               "search_cpu_realtime_factor", "timings", "share_seconds", "peak_memory_mb", "embedding_seconds",
               "tile_seconds"}


def _env(name):
    value = os.environ.get(name)
    if not value:
        pytest.skip(f"{name} is not set (run the tests through ctest)")
    return value


@pytest.fixture(scope="session")
def cli():
    """Runs the CLI; returns the completed process (check=False: tests look at failures)."""
    binary = _env("MOTIONGRAPH")

    def run(*args, check=True):
        done = subprocess.run([binary, *map(str, args)], capture_output=True, text=True)
        if check and done.returncode != 0:
            raise AssertionError(f"motiongraph {' '.join(map(str, args))} failed: {done.stderr}")
        return done

    return run


@pytest.fixture(scope="session")
def data():
    return Path(_env("MOTIONGRAPH_DATA"))


@pytest.fixture(scope="session")
def graph_file():
    return Path(_env("MOTIONGRAPH_TEST_GRAPH"))


@pytest.fixture(scope="session")
def graph(graph_file):
    return mg.load_graph(str(graph_file))


def cli_error(done):
    """The CLI's message: stderr's last line (without a 'motiongraph: ' prefix)."""
    assert done.returncode != 0
    line = done.stderr.strip().splitlines()[-1]
    return line.removeprefix("motiongraph: ")


def without_timings(value):
    if isinstance(value, dict):
        return {k: without_timings(v) for k, v in value.items() if k not in TIMING_KEYS}
    if isinstance(value, list):
        return [without_timings(v) for v in value]
    return value


def read_json(path):
    return json.loads(Path(path).read_text())


def assert_positions_equal(motion, cli_json):
    """Positions within 1e-6 m of the CLI's JSON (which rounds them to the micrometre)."""
    want = np.asarray(cli_json["positions"], dtype=float)
    assert motion.positions.shape == want.shape
    assert np.max(np.abs(motion.positions - want)) <= 1e-6
    assert motion.joint_names == [j["name"] for j in cli_json["joints"]]
    assert motion.parents == [j["parent"] for j in cli_json["joints"]]
    assert motion.fps == cli_json["fps"]


def assert_releases_the_gil(work):
    """Runs work() on a thread while this one ticks: had work() held the GIL all along, this
    thread would have stood still for all of it, one gap as long as the work."""
    import threading
    import time

    times = {}

    def run():
        times["begin"] = time.perf_counter()
        work()
        times["end"] = time.perf_counter()

    thread = threading.Thread(target=run)
    last = time.perf_counter()
    longest = 0.0
    thread.start()
    while thread.is_alive():
        now = time.perf_counter()
        longest = max(longest, now - last)
        last = now
    thread.join()
    duration = times["end"] - times["begin"]
    assert duration > 0.05, "too short to tell"
    assert longest < duration / 2, (longest, duration)


def glb_json(path):
    """The JSON chunk of a binary glTF file."""
    data = path.read_bytes()
    length = int.from_bytes(data[12:16], "little")
    assert data[16:20] == b"JSON"
    return json.loads(data[20:20 + length])


def assert_bare_glb(bare, figured):
    """The glTF without its stick figure has the same joints, skin and animation, and no mesh."""
    without, with_figure = glb_json(bare), glb_json(figured)
    assert "meshes" in with_figure and "meshes" not in without
    assert without["skins"][0]["joints"] == with_figure["skins"][0]["joints"]
    joints = [n["name"] for n in with_figure["nodes"] if "mesh" not in n]
    assert [n["name"] for n in without["nodes"]] == joints
    assert len(without["animations"][0]["channels"]) == len(with_figure["animations"][0]["channels"])
