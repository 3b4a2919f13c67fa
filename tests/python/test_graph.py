"""build(), load_graph() and Graph: the same graph, report and exports as the CLI's build."""
import re

import numpy as np
import pytest

import motiongraph as mg
from conftest import assert_releases_the_gil, cli_error, read_json, without_timings


def inspect_nodes(cli, path):
    """The CLI's 'inspect --nodes' table as (frame, clip, tags) per node, in node order."""
    rows = []
    for line in cli("inspect", path, "--nodes").stdout.splitlines():
        m = re.match(r"\s*(\d+)\s+(\d+)\s+(\S+)\s+[\d.]+s\s+\d+\s+\d+\s*(\S*)$", line)
        if m:
            assert int(m.group(1)) == len(rows)
            rows.append((int(m.group(2)), m.group(3), m.group(4).split(",") if m.group(4) else []))
    assert rows
    return rows


def python_nodes(graph):
    return [(n["frame"], n["clip"], n["tags"]) for n in graph.nodes]


@pytest.fixture(scope="module")
def cli_build(cli, data, tmp_path_factory):
    out = tmp_path_factory.mktemp("cli_build")
    cli("build", data / "cmu/16", "-o", out / "g.mgraph", "--report", out / "report.json", "--no-cache",
        "--export-matrix", out / "matrix.npy", "--export-clouds", out / "clouds.npy", "-q")
    return out


@pytest.fixture(scope="module")
def built(data):
    return mg.build(str(data / "cmu/16"), no_cache=True, distance_matrix=True, clouds=True)


def test_build_equals_the_cli(cli, cli_build, built):
    assert without_timings(built.report) == without_timings(read_json(cli_build / "report.json"))
    from_cli = mg.load_graph(str(cli_build / "g.mgraph"))
    assert (built.node_count, built.edge_count, built.transition_count, built.frame_count) == (
        from_cli.node_count, from_cli.edge_count, from_cli.transition_count, from_cli.frame_count)
    assert built.threshold == from_cli.threshold
    assert python_nodes(built) == inspect_nodes(cli, cli_build / "g.mgraph")
    after = built.report["graph_after"]
    assert (after["nodes"], after["edges"], after["transitions"]) == (
        built.node_count, built.edge_count, built.transition_count)


def test_a_built_graph_plays_what_its_file_plays(cli_build, built, tmp_path):
    """build()'s graph is the file's: the same motion to the bit as the CLI's graph and as itself
    saved and read back."""
    built.save(tmp_path / "g.mgraph")
    graphs = [built, mg.load_graph(tmp_path / "g.mgraph"), mg.load_graph(cli_build / "g.mgraph")]
    paths = [g.path(shape="figure8:4", segments=["walk:0-25", "run:25-51"]) for g in graphs]
    walks = [g.walk(0, 7, min_frames=60) for g in graphs]
    for made in (paths, walks):
        assert made[0].report["expansions"] == made[1].report["expansions"] == made[2].report["expansions"]
        assert np.array_equal(made[0].positions, made[1].positions)
        assert np.array_equal(made[0].positions, made[2].positions)


def test_exports_equal_the_cli(cli_build, built):
    matrix = built.distance_matrix()
    assert matrix.shape == (built.frame_count, built.frame_count) and matrix.dtype == np.float32
    assert np.array_equal(matrix, np.load(cli_build / "matrix.npy"), equal_nan=True)
    clouds = built.clouds()
    assert clouds.shape[0] == built.frame_count and clouds.shape[2] == 3
    assert np.array_equal(clouds, np.load(cli_build / "clouds.npy"))


def test_saved_graph_reads_back(cli, built, tmp_path):
    built.save(str(tmp_path / "g.mgraph"))
    again = mg.load_graph(str(tmp_path / "g.mgraph"))
    assert python_nodes(again) == python_nodes(built)
    assert inspect_nodes(cli, tmp_path / "g.mgraph") == python_nodes(built)
    assert without_timings(again.report) == without_timings(built.report)
    with pytest.raises(mg.Error, match=r"no distance_matrix: only a graph built with distance_matrix=True holds it \(a "
                       r"\.mgraph file keeps none\)"):
        again.distance_matrix()
    assert built.name == str(tmp_path / "g.mgraph")  # messages name the file it now is


def test_nodes_are_made_once_and_handed_out_as_copies(graph):
    nodes = graph.nodes
    assert nodes == graph.nodes and nodes is not graph.nodes
    nodes[0]["tags"].append("changed")
    nodes[1]["clip"] = "changed"
    assert "changed" not in graph.nodes[0]["tags"] and graph.nodes[1]["clip"] != "changed"


def test_edges_are_the_graph_as_the_reports_number_it(graph):
    """Graph.edges: numbered as a walk's report numbers its edges (each follows the one before it),
    clip pieces between their nodes' frames, transitions with their D and its RMS as the build
    reports its threshold; handed out as copies."""
    edges, nodes = graph.edges, graph.nodes
    weight = graph.report["threshold"] / (graph.report["threshold_rms_cm"] / 100) ** 2
    assert len(edges) == graph.edge_count
    assert sum(e["kind"] != "clip" for e in edges) == graph.transition_count
    assert {e["kind"] for e in edges} == {"clip", "transition", "bridge"}
    for e in edges:
        assert e["from_frame"] == nodes[e["from"]]["frame"] or e["kind"] != "clip", e
        if e["kind"] == "clip":
            assert (e["to_frame"], e["distance"], e["rms_cm"]) == (nodes[e["to"]]["frame"], None, None), e
            assert e["frames"] == e["to_frame"] - e["from_frame"] and nodes[e["from"]]["clip"] == nodes[e["to"]]["clip"]
        else:
            assert e["distance"] > 0 and e["rms_cm"] == pytest.approx(100 * np.sqrt(e["distance"] / weight), rel=1e-6)
    motion = graph.path(shape="figure8:4")
    walk = motion.report["edges"]
    assert all(edges[a]["to"] == edges[b]["from"] for a, b in zip(walk, walk[1:]))
    assert edges[walk[0]]["from"] == motion.report["start_node"]
    assert sum(edges[e]["kind"] != "clip" for e in walk) == motion.report["transitions"]
    assert sum(edges[e]["kind"] == "bridge" for e in walk) == motion.report["bridges"]
    edges[0]["kind"] = "changed"
    assert graph.edges[0]["kind"] == "clip"
    # Each motion type's own threshold: the lowest is Graph.threshold, and every transition (not
    # bridge: those lie above) passes the highest; in cm as the edges give theirs.
    own = graph.tag_thresholds
    assert own and set(own) <= set(graph.tags), own
    assert min(t["threshold"] for t in own.values()) == pytest.approx(graph.threshold)
    highest = max(t["threshold"] for t in own.values())
    assert all(e["distance"] <= highest * (1 + 1e-6) for e in edges if e["kind"] == "transition")
    assert any(e["distance"] > graph.threshold for e in edges if e["kind"] == "transition")
    for t in own.values():
        assert t["rms_cm"] == pytest.approx(100 * np.sqrt(t["threshold"] / weight), rel=1e-6)


def test_fixture_graph_equals_a_python_build(cli, data, graph_file, graph):
    """The library-made test graph (the CLI's defaults) is what build() makes with no options."""
    assert python_nodes(graph) == inspect_nodes(cli, graph_file)
    assert python_nodes(mg.build([data / "cmu/16"], no_cache=True)) == python_nodes(graph)


def test_options_as_the_cli(cli, data, tmp_path):
    cli("build", data / "cmu/16", "-o", tmp_path / "g.mgraph", "--report", tmp_path / "r.json", "--no-cache", "-q",
        "--threshold", "4cm", "--cloud", "joints", "--joint-weight", "head=2", "--connect-tags", "walk,run",
        "--no-tag-thresholds", "--fps", 24)
    graph = mg.build([str(data / "cmu/16")], no_cache=True, threshold="4cm", cloud="joints",
                     joint_weight={"head": 2}, connect_tags=["walk", "run"], no_tag_thresholds=True, fps=24)
    assert without_timings(graph.report) == without_timings(read_json(tmp_path / "r.json"))
    assert python_nodes(graph) == inspect_nodes(cli, tmp_path / "g.mgraph")


def test_the_path_check_mirror_can_be_left_out(data, built):
    # By default each threshold is judged by the worse of the test path and its mirror; with
    # no_path_check_mirror=True (the CLI's --no-path-check-mirror) by the test path alone.
    assert built.report["path_check"]["mirrored"] is True
    one = mg.build(str(data / "cmu/16"), no_path_check_mirror=True)
    check = one.report["path_check"]
    assert check["mirrored"] is False and all(p["probe_deviations_m"][1] is None for p in check["points"])
    assert check["threshold"] <= built.report["path_check"]["threshold"]


def test_cache_dir_gives_the_same_graph(data, built, tmp_path):
    first = mg.build(str(data / "cmu/16"), cache_dir=str(tmp_path))
    assert any(tmp_path.iterdir())
    second = mg.build(str(data / "cmu/16"), cache_dir=str(tmp_path))
    assert python_nodes(first) == python_nodes(second) == python_nodes(built)


@pytest.mark.parametrize("cli_args, options", [
    (["--cloud", "bad"], {"cloud": "bad"}),
    (["--taper", "x"], {"taper": "x"}),
    (["--threshold", "abc"], {"threshold": "abc"}),
    (["--threshold", "4cm", "--threshold-quantile", "0.1"], {"threshold": "4cm", "threshold_quantile": 0.1}),
    (["--joint-weight", "head"], {"joint_weight": ["head"]}),
    (["--coverage", "2"], {"coverage": 2.0}),
    (["--threshold-quantile", "-0.5"], {"threshold_quantile": -0.5}),
    (["--joint-weight", "lhead=2"], {"joint_weight": ["lhead=2"]}),
])
def test_bad_options_raise_the_cli_message(cli, data, tmp_path, cli_args, options):
    want = cli_error(cli("build", data / "cmu/16", "-o", tmp_path / "g.mgraph", "--no-cache", *cli_args, check=False))
    with pytest.raises(mg.Error) as raised:
        mg.build(str(data / "cmu/16"), no_cache=True, **options)
    assert str(raised.value) == want


def test_input_and_output_errors_raise_the_cli_message(cli, data, tmp_path, built):
    missing = tmp_path / "missing"
    want = cli_error(cli("build", missing, "-o", tmp_path / "g.mgraph", "--no-cache", check=False))
    with pytest.raises(mg.Error) as raised:
        mg.build(str(missing), no_cache=True)
    assert str(raised.value) == want
    want = cli_error(cli("build", data / "cmu/16", "-o", tmp_path / "g.txt", check=False))
    with pytest.raises(mg.Error) as raised:
        built.save(str(tmp_path / "g.txt"))
    assert str(raised.value) == want
    want = cli_error(cli("path", missing / "g.mgraph", "--shape", "line:5", "-o", tmp_path / "o.json", check=False))
    with pytest.raises(mg.Error) as raised:
        mg.load_graph(str(missing / "g.mgraph"))
    assert str(raised.value) == want
    with pytest.raises(TypeError, match="unexpected keyword argument 'windw'"):
        mg.build(str(data / "cmu/16"), windw=10)


def test_empty_graph_raises_with_the_report(cli, data, tmp_path):
    args = ["--threshold", "0.01cm", "--no-cache"]
    done = cli("build", data / "cmu/16", "-o", tmp_path / "g.mgraph", "--report", tmp_path / "r.json", *args,
               check=False)
    with pytest.raises(mg.EmptyGraphError) as raised:
        mg.build(str(data / "cmu/16"), threshold="0.01cm", no_cache=True)
    assert str(raised.value) == cli_error(done)
    assert isinstance(raised.value, mg.Error)
    assert without_timings(raised.value.report) == without_timings(read_json(tmp_path / "r.json"))


def test_progress_callback(data):
    lines = []
    mg.build(str(data / "cmu/16"), no_cache=True, progress=lines.append)
    assert lines and all(isinstance(line, str) and line for line in lines)
    # What cannot be called is said before anything is read, not at the first line.
    with pytest.raises(TypeError, match=r"build\(\): progress must be callable"):
        mg.build(str(data / "no such folder"), progress=5)


def _cached(folder):
    return folder.exists() and any(folder.iterdir())


def test_an_exception_in_progress_stops_the_build(data, tmp_path):
    # Its first line comes after reading: the build stops before the distance stage, which
    # would otherwise be cached.
    def stop(line):
        raise ValueError("enough: " + line)

    with pytest.raises(ValueError, match="enough: 15 clips"):
        mg.build(data / "cmu/16", cache_dir=tmp_path / "cache", progress=stop)
    assert not _cached(tmp_path / "cache")
    mg.build(data / "cmu/16", cache_dir=tmp_path / "cache")  # the next build is not stopped
    assert _cached(tmp_path / "cache")


def test_ctrl_c_stops_the_build(data, tmp_path):
    import _thread

    # As Ctrl-C does, at the first line: the signal's flag set, Python's handler left to run on the
    # main thread (which looks every 50 ms: the callback gives it the time).
    import time

    lines = []

    def interrupt(line):
        lines.append(line)
        if len(lines) == 1:
            _thread.interrupt_main()
            time.sleep(0.5)

    with pytest.raises(KeyboardInterrupt):
        mg.build(data / "cmu/16", cache_dir=tmp_path / "cache", progress=interrupt)
    assert not _cached(tmp_path / "cache")
    assert not any("distance stage" in line for line in lines), lines


def test_paths_may_be_path_objects(data, graph_file, tmp_path):
    graph = mg.load_graph(graph_file)
    graph.save(tmp_path / "g.mgraph")
    assert mg.load_graph(tmp_path / "g.mgraph").nodes == graph.nodes
    # Path-valued keywords too, and bytes, as one path each.
    cached = mg.build(data / "cmu/16", cache_dir=tmp_path / "cache")
    assert any((tmp_path / "cache").iterdir()) and cached.nodes == graph.nodes
    assert mg.build(bytes(data / "cmu/16"), cache_dir=tmp_path / "cache").nodes == graph.nodes
    assert len(mg.load_library(bytes(data / "cmu/16"))) == len(mg.load_library(data / "cmu/16"))
    (tmp_path / "line.json").write_text('{"points": [[0, 0], [0, -6]]}')
    assert graph.path(file=tmp_path / "line.json").report["reached_end"]
    with pytest.raises(TypeError, match="'cache_dir' cannot be a int"):
        mg.build(data / "cmu/16", cache_dir=3)


def test_values_the_cli_refuses_are_refused(data, graph, tmp_path):
    with pytest.raises(TypeError, match="'threshold' cannot be a bool"):
        mg.build(data / "cmu/16", threshold=True)
    # A skeleton given for AMC files must be there, as the CLI's --asf must, with a folder too.
    with pytest.raises(mg.Error, match="none.asf: no such file"):
        mg.build(data / "cmu/16", asf=tmp_path / "none.asf")
    with pytest.raises(mg.Error, match="the start node must be >= 0, not -2"):
        graph.path(shape="line:5", start_node=-2)
    with pytest.raises(mg.Error, match="the beam width must be from 0 to 1000000, not -1"):
        graph.controller(beam=-1)
    # Numbers as the CLI's options take them: finite (horizon=inf ran, its report saying 5 s), not
    # True (a 1 s horizon), integers in their range, and a horizon of at most a minute (1e5 s ran
    # out of memory).
    for keyword in ("min_speed", "behind_penalty", "horizon", "retry_deviation", "edit_max_turn"):
        for value in (float("inf"), float("nan")):
            with pytest.raises(ValueError, match=f"path\\(\\) keyword argument '{keyword}' must be a finite number"):
                graph.path(shape="line:5", **{keyword: value})
    with pytest.raises(ValueError, match="controller\\(\\) keyword argument 'bridge_penalty' must be a finite number"):
        graph.controller(bridge_penalty=float("inf"))
    with pytest.raises(TypeError, match="'horizon' cannot be a bool"):
        graph.path(shape="line:5", horizon=True)
    with pytest.raises(TypeError, match="'start_node' cannot be a bool"):
        graph.path(shape="line:5", start_node=True)
    with pytest.raises(ValueError, match="'seed' must be an integer from 0 to [0-9]+, not -1"):
        graph.walk(0, 1, cost="random", seed=-1)
    assert graph.walk(0, 1, cost="random", seed=2**64 - 1).report["seed"] == 2**64 - 1  # the whole range
    with pytest.raises(ValueError, match=f"'seed' must be an integer from 0 to {2**64 - 1}, not {2**64}"):
        graph.walk(0, 1, cost="random", seed=2**64)
    with pytest.raises(ValueError, match="'beam' must be an integer from -2147483648 to 2147483647"):
        graph.path(shape="line:5", beam=2**31)
    with pytest.raises(mg.Error, match="path search: the horizon must be above 0 s and at most 60 s, not 100000 s"):
        graph.path(shape="line:5", horizon=1e5)
    with pytest.raises(mg.Error, match="controller: the horizon must be above 0 s and at most 60 s"):
        graph.controller(horizon=61)


def test_build_warnings_point_at_the_caller(data):
    clip = data / "cmu/16/16_15.amc"
    with pytest.warns(UserWarning, match="a clip is named 16_15 already") as caught:
        mg.build([clip, clip], no_cache=True, no_path_check=True, threshold_quantile=0.2)
    assert caught[0].filename == __file__, caught[0].filename


def test_build_releases_the_gil(data):
    assert_releases_the_gil(lambda: mg.build(str(data / "cmu/16"), no_cache=True))


def test_wrong_keyword_types_raise_type_error(data, graph):
    with pytest.raises(TypeError, match="'window' cannot be a str"):
        mg.build(str(data / "cmu/16"), window="ten")
    with pytest.raises(TypeError, match="'seed' cannot be a str"):
        graph.walk(0, 1, seed="x")
