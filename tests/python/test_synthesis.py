"""Graph.walk(), Graph.path() and the controller: the same motion and reports as the CLI's
walk, path and steer on the subject-16 graph."""
import json
import re
import warnings

import numpy as np
import pytest

import motiongraph as mg
from conftest import (assert_bare_glb, assert_positions_equal, assert_releases_the_gil, cli_error, glb_json, read_json,
                      without_timings)

FIGURE8 = ["--shape", "figure8:4", "--segment", "walk:0-25", "--segment", "run:25-51"]


def test_path_equals_the_cli(cli, graph_file, graph, tmp_path):
    cli("path", graph_file, *FIGURE8, "-o", tmp_path / "cli.json", "--report", tmp_path / "cli-report.json")
    motion = graph.path(shape="figure8:4", segments=["walk:0-25", "run:25-51"])
    cli_json = read_json(tmp_path / "cli.json")
    assert_positions_equal(motion, cli_json)
    report = read_json(tmp_path / "cli-report.json")
    assert without_timings(motion.report) == without_timings(report)
    assert motion.report["reached_end"] and motion.report["seconds"] > 0
    # save() writes the CLI's file, the feet's contacts included.
    motion.save(str(tmp_path / "py.json"))
    assert (tmp_path / "py.json").read_bytes() == (tmp_path / "cli.json").read_bytes()
    assert "contacts" in cli_json
    # With a root-motion joint, as the CLI's --root-motion writes it.
    (tmp_path / "cli").mkdir()
    (tmp_path / "py").mkdir()
    cli("path", graph_file, *FIGURE8, "--root-motion", "--root-motion-smoothing", 0.25, "-o", tmp_path / "cli" / "rm.glb")
    motion.save(str(tmp_path / "py" / "rm.glb"), root_motion=True, root_motion_smoothing=0.25)
    assert (tmp_path / "py" / "rm.glb").read_bytes() == (tmp_path / "cli" / "rm.glb").read_bytes()
    # Without the stick figure, as --no-figure writes it.
    cli("path", graph_file, *FIGURE8, "--root-motion", "--root-motion-smoothing", 0.25, "--no-figure", "-o",
        tmp_path / "cli" / "bare.glb")
    motion.save(str(tmp_path / "py" / "bare.glb"), root_motion=True, root_motion_smoothing=0.25, figure=False)
    assert (tmp_path / "py" / "bare.glb").read_bytes() == (tmp_path / "cli" / "bare.glb").read_bytes()
    assert_bare_glb(tmp_path / "py" / "bare.glb", tmp_path / "py" / "rm.glb")
    # .contacts and .foot_joints are the file's, as arrays.
    assert motion.foot_joints == cli_json["contacts"]["joints"]
    planted = motion.contacts
    assert planted.dtype == bool and planted.shape == (len(motion), len(motion.foot_joints))
    np.testing.assert_array_equal(planted, np.array(cli_json["contacts"]["planted"], dtype=bool))


def test_path_from_points_and_options(cli, graph_file, graph, tmp_path):
    points = [[0.0, 0.0], [0.0, -6.0], [4.0, -10.0], [8.0, -10.0]]
    (tmp_path / "path.json").write_text(json.dumps({"points": points}))
    options = ["--horizon", 2, "--transition-penalty", 0.5, "--bridge-penalty", 7, "--beam", 16, "--no-cleanup", "--edit-max-turn", 30,
               "--progress-retries", 1, "--retry-horizon", 4, "--edit-round-corners", 1]
    cli("path", graph_file, "--path", tmp_path / "path.json", *options, "-o", tmp_path / "cli.json",
        "--report", tmp_path / "r.json")
    want = read_json(tmp_path / "cli.json")
    kwargs = dict(horizon=2, transition_penalty=0.5, bridge_penalty=7, beam=16, cleanup=False, edit_max_turn=30,
                  progress_retries=1, retry_horizon=4, edit_round_corners=1)
    for motion in (graph.path(points=points, **kwargs), graph.path(points=np.array(points), **kwargs),
                   graph.path(file=str(tmp_path / "path.json"), **kwargs)):
        assert_positions_equal(motion, want)
        report = without_timings(motion.report)
        cli_report = without_timings(read_json(tmp_path / "r.json"))
        # The one difference: how the clean-up was turned off.
        assert report.pop("cleanup") == {"enabled": False, "reason": "cleanup=False"}
        assert cli_report.pop("cleanup") == {"enabled": False, "reason": "--no-cleanup"}
        assert report == cli_report
        assert report["path_edit"]["max_turn_deg_per_m"] == 30 and report["path_edit"]["edited"]
        assert report["path_edit"]["round_corners_m"] == 1
        assert report["horizon_s"] in ((2, 4) if report["attempts"] == 2 else (2,))  # the retry's look: 4 s
    # path_edit=False is --no-path-edit: the walk as the graph plays it.
    cli("path", graph_file, "--path", tmp_path / "path.json", *options, "--no-path-edit", "-o", tmp_path / "plain.json")
    assert_positions_equal(graph.path(points=points, path_edit=False, **kwargs), read_json(tmp_path / "plain.json"))


def test_tag_lookahead_reaches_the_path(cli, graph_file, graph, tmp_path):
    """tag_lookahead is the path's --tag-lookahead: at 0 (each search sees its horizon only) the
    same motion from both, another than the default's."""
    cli("path", graph_file, *FIGURE8, "--tag-lookahead", 0, "-o", tmp_path / "cli.json")
    want = read_json(tmp_path / "cli.json")
    blind = graph.path(shape="figure8:4", segments=["walk:0-25", "run:25-51"], tag_lookahead=0)
    assert_positions_equal(blind, want)
    default = graph.path(shape="figure8:4", segments=["walk:0-25", "run:25-51"])
    assert len(default) != len(blind) or np.max(np.abs(default.positions - blind.positions)) > 1e-3


def test_retry_tag_match_reaches_the_path(cli, graph_file, graph, tmp_path):
    """retry_tag_match is the path's --retry-tag-match: with the run priced too low to matter the
    first search walks on; at 0 it is kept (one attempt, the CLI's motion), by default it is
    searched again."""
    cli("path", graph_file, *FIGURE8, "--tag-penalty", 0.01, "--retry-tag-match", 0, "-o", tmp_path / "cli.json")
    want = read_json(tmp_path / "cli.json")
    kept = graph.path(shape="figure8:4", segments=["walk:0-25", "run:25-51"], tag_penalty=0.01, retry_tag_match=0)
    assert_positions_equal(kept, want)
    assert kept.report["attempts"] == 1
    again = graph.path(shape="figure8:4", segments=["walk:0-25", "run:25-51"], tag_penalty=0.01)
    assert again.report["attempts"] > 1
    assert again.report["tag_penalty_m2"] > 0.01
    with pytest.raises(mg.Error, match="tag match"):
        graph.path(shape="figure8:4", retry_tag_match=2)


def test_what_a_path_falls_short_of_is_warned_of_as_the_cli_does(cli, graph_file, graph, tmp_path):
    """A circle of half a metre is followed further off than the retries look for, and a search
    of one edge does not reach the end: each says so as a UserWarning with the CLI's warning, and
    the report carries it ("shortfalls"); a path followed well says nothing."""
    with pytest.warns(UserWarning, match=r"follows the path [\d.]+ m off on average") as caught:
        circle = graph.path(shape="circle:0.5")
    assert [str(w.message) for w in caught] == [f"{graph.name}: {s}" for s in circle.report["shortfalls"]]
    cli("path", graph_file, "--shape", "circle:0.5", "-o", tmp_path / "c.json", "--report", tmp_path / "c-report.json")
    assert read_json(tmp_path / "c-report.json")["shortfalls"] == circle.report["shortfalls"]
    with pytest.warns(UserWarning, match="did not reach the path's end: it went [\\d.]+ m of 20.0 m"):
        stuck = graph.path(shape="line:20", max_expansions=1, beam=0, progress_retries=0)
    assert not stuck.report["reached_end"]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        followed = graph.path(shape="line:20")
    assert followed.report["shortfalls"] == []


def test_a_type_the_graph_does_not_play_is_warned_of(data):
    """A graph at 1 cm keeps walking alone: a path or a controller asking it to run warns, naming
    the segment, as the CLI does; the controller once however often it is asked."""
    with pytest.warns(UserWarning, match="the graph keeps 2 % of the frames"):  # as the build says
        walking = mg.build(str(data / "cmu/16"), threshold="1cm", no_cache=True)
    with pytest.warns(UserWarning, match=r"the segment 5-10 m asks for 'run', which the graph plays in no frame") as caught:
        motion = walking.path(shape="line:10", segments=["walk:0-5", "run:5-10"])
    assert len([w for w in caught if "plays in no frame" in str(w.message)]) == 1
    run = motion.report["segments"][1]
    assert run["graph_frames"] == 0 and run["clip_frames"] > 0 and run["tag_match"] == 0, run
    assert [str(w.message) for w in caught] == [f"{walking.name}: {w}" for w in motion.report["warnings"]]
    with pytest.warns(UserWarning, match="the controller asks for 'run'") as caught:
        controller = walking.controller(heading_deg=0, tag="walk")
        controller.step(0, "run")
        controller.step(90, "run")
    assert len([w for w in caught if "plays in no frame" in str(w.message)]) == 1
    # The controller's report carries what it said (once), as the CLI's steer report does.
    said = [str(w.message) for w in caught]
    assert [f"{walking.name}: {w}" for w in controller.motion.report["warnings"]] == said, said


def test_walk_equals_the_cli(cli, graph_file, graph, tmp_path):
    cli("walk", graph_file, "--from", 0, "--to", 7, "--cost", "hybrid", "--seed", 3, "--min-frames", 60,
        "-o", tmp_path / "cli.json", "--report", tmp_path / "r.json")
    motion = graph.walk(0, 7, cost="hybrid", seed=3, min_frames=60)
    assert_positions_equal(motion, read_json(tmp_path / "cli.json"))
    assert without_timings(motion.report) == without_timings(read_json(tmp_path / "r.json"))
    assert len(motion) >= 60
    motion.save(str(tmp_path / "py.bvh"))
    cli("walk", graph_file, "--from", 0, "--to", 7, "--cost", "hybrid", "--seed", 3, "--min-frames", 60,
        "-o", tmp_path / "cli.bvh")
    assert (tmp_path / "py.bvh").read_bytes() == (tmp_path / "cli.bvh").read_bytes()


def test_results_of_one_graph_as_an_animation_set(graph, tmp_path):
    """A walk, a path and steering of one graph: one .glb, an animation each, all keying the same
    joints, at rest as the first one's own file is."""
    controller = graph.controller()
    for _ in range(30):
        controller.step(90.0)
    motions = [graph.walk(0, 7, cost="hybrid", seed=3, min_frames=60), graph.path(shape="line:6"), controller.motion]
    mg.save_animations(str(tmp_path / "set.glb"), motions, root_motion=True)
    gltf = glb_json(tmp_path / "set.glb")
    assert [a["name"] for a in gltf["animations"]] == ["walk", "path", "steer"]
    motions[0].save(str(tmp_path / "walk.glb"), root_motion=True)
    assert glb_json(tmp_path / "walk.glb")["nodes"] == gltf["nodes"]
    keyed = [{(c["target"]["node"], c["target"]["path"]) for c in a["channels"]} for a in gltf["animations"]]
    assert keyed[0] == keyed[1] == keyed[2]
    for animation, motion in zip(gltf["animations"], motions):
        assert gltf["accessors"][animation["samplers"][0]["input"]]["count"] == len(motion)
    # None is a keyword's default, as for build().
    np.testing.assert_array_equal(graph.path(shape="line:6", start_node=None, horizon=None).positions,
                                  motions[1].positions)
    again = graph.controller(start_node=None)
    for _ in range(30):
        again.step(90.0)
    np.testing.assert_array_equal(again.motion.positions, controller.motion.positions)


def test_steering_equals_the_cli(cli, graph_file, graph, tmp_path):
    controls = [{"at_s": 0, "heading_deg": 0, "tag": "walk"}, {"at_s": 2, "heading_deg": 90, "tag": "any"},
                {"at_s": 4, "heading_deg": 200, "tag": "run"}]
    (tmp_path / "controls.json").write_text(json.dumps({"duration_s": 6, "controls": controls}))
    cli("steer", graph_file, "--script", tmp_path / "controls.json", "--bridge-penalty", 3, "-o", tmp_path / "cli.json",
        "--report", tmp_path / "cli-report.json")
    fps = graph.fps
    total = round(6 * fps)

    def control(frame):
        return [c for c in controls if c["at_s"] <= frame / fps][-1]

    controller = graph.controller(heading_deg=0, tag="walk", bridge_penalty=3)
    frames = 0
    while frames < total:
        c = control(frames)
        step = controller.step(c["heading_deg"], None if c["tag"] == "any" else c["tag"])
        assert len(step) > 0
        np.testing.assert_array_equal(step.positions, controller.motion.positions[frames:])
        np.testing.assert_array_equal(step.contacts, controller.motion.contacts[frames:])
        frames += len(step)
    motion = controller.motion
    assert len(motion) == frames
    want = read_json(tmp_path / "cli.json")
    assert np.max(np.abs(motion.positions[:total] - np.asarray(want["positions"]))) <= 1e-6
    assert motion.foot_joints == want["contacts"]["joints"]
    np.testing.assert_array_equal(motion.contacts[:total], np.array(want["contacts"]["planted"], dtype=bool))
    # The report, as the CLI's of the same decisions (the CLI's cut at the script's end).
    report, cli_report = motion.report, read_json(tmp_path / "cli-report.json")
    assert report["frames"] == frames and report["fps"] == fps
    assert report["edges"] == cli_report["edges"] and report["decisions"] == cli_report["decisions"]
    # (the CLI counts the transitions that start before the script's end; these, every one)
    assert report["transitions"] >= cli_report["transitions"] and report["bridges"] >= cli_report["bridges"]
    assert report["transitions"] > 0
    assert report["transitions_per_second"] == pytest.approx(report["transitions"] / (frames / fps))
    assert report["heading_edit"] == cli_report["heading_edit"] and report["cleanup"] == cli_report["cleanup"]
    assert report["budget_exhausted_decisions"] == cli_report["budget_exhausted_decisions"]
    assert report["foot_slide"]["source"]["clips"] and report["foot_slide"]["ratio"]["mean_mps"] >= 0
    assert controller.motion.report == report  # the same, asked again


def test_tag_lookahead_reaches_the_controller(cli, graph_file, graph, tmp_path):
    """tag_lookahead is the CLI's --tag-lookahead: the same motion at 0 (the horizon only) from
    both; out of 0..1 it is refused."""
    controls = [{"at_s": 0, "heading_deg": 0, "tag": "walk"}, {"at_s": 1, "heading_deg": 0, "tag": "run"}]
    (tmp_path / "controls.json").write_text(json.dumps({"duration_s": 4, "controls": controls}))
    cli("steer", graph_file, "--script", tmp_path / "controls.json", "--tag-lookahead", 0, "-o", tmp_path / "cli.json")
    want = np.asarray(read_json(tmp_path / "cli.json")["positions"])
    controller = graph.controller(heading_deg=0, tag="walk", tag_lookahead=0)
    while len(controller.motion) < len(want):
        tag = "walk" if len(controller.motion) < graph.fps else "run"
        controller.step(0, tag)
    assert np.max(np.abs(controller.motion.positions[:len(want)] - want)) <= 1e-6
    with pytest.raises(mg.Error, match="lookahead"):
        graph.controller(tag_lookahead=1.5)


def test_travel_pace_reaches_the_controller(cli, graph_file, graph, tmp_path):
    """travel_pace and travel_penalty are the CLI's --travel-pace and --travel-penalty: the same
    motion asked for no tag from both; a negative pace is refused."""
    controls = [{"at_s": 0, "heading_deg": 0}, {"at_s": 1.5, "heading_deg": 120}]
    (tmp_path / "controls.json").write_text(json.dumps({"duration_s": 4, "controls": controls}))
    cli("steer", graph_file, "--script", tmp_path / "controls.json", "--travel-pace", 1.5, "--travel-penalty", 4,
        "-o", tmp_path / "cli.json")
    want = np.asarray(read_json(tmp_path / "cli.json")["positions"])
    controller = graph.controller(heading_deg=0, travel_pace=1.5, travel_penalty=4)
    while len(controller.motion) < len(want):
        controller.step(0 if len(controller.motion) < 1.5 * graph.fps else 120)
    assert np.max(np.abs(controller.motion.positions[:len(want)] - want)) <= 1e-6
    default = graph.controller(heading_deg=0)
    while len(default.motion) < len(want):
        default.step(0 if len(default.motion) < 1.5 * graph.fps else 120)
    assert np.max(np.abs(default.motion.positions[:len(want)] - want)) > 0.01  # (the keywords were heard)
    with pytest.raises(mg.Error, match="travel pace"):
        graph.controller(travel_pace=-1)


def test_rest_equals_the_cli_and_stands_still(cli, graph_file, graph, tmp_path):
    controls = [{"at_s": 0, "heading_deg": 0, "tag": "walk"}, {"at_s": 2, "rest": True}]
    (tmp_path / "controls.json").write_text(json.dumps({"duration_s": 9, "controls": controls}))
    cli("steer", graph_file, "--script", tmp_path / "controls.json", "-o", tmp_path / "cli.json",
        "--report", tmp_path / "cli-report.json")
    fps = graph.fps
    controller = graph.controller(heading_deg=0, tag="walk")
    while len(controller.motion) < 9 * fps:
        rest = len(controller.motion) >= 2 * fps
        controller.step(0, "walk", rest=rest)
        if not rest:
            assert controller.rest_s is None
        # Standing once the frame from which it stands still is played (resting from the way there on).
        still = controller.rest_s is not None and len(controller.motion) > round(controller.rest_s * fps)
        assert controller.standing == still and (controller.resting or not still)
    motion, want = controller.motion, read_json(tmp_path / "cli.json")
    total = len(want["positions"])
    assert np.max(np.abs(motion.positions[:total] - np.asarray(want["positions"]))) <= 1e-6
    np.testing.assert_array_equal(motion.contacts[:total], np.array(want["contacts"]["planted"], dtype=bool))
    rest = read_json(tmp_path / "cli-report.json")["rest"]
    assert motion.report["rest"] == rest and controller.rest_s == rest["at_s"] > 2
    assert controller.resting
    # Standing still from then on, whatever it is asked: the last frame held.
    root = motion.positions[:, 0, :]
    still = int(np.ceil(rest["at_s"] * fps))
    assert np.max(np.linalg.norm((root[still:] - root[still])[:, [0, 2]], axis=1)) < 0.1
    assert controller.standing
    # Asked to turn while it stands: not heard, said once (as the CLI's steer warns).
    with pytest.warns(UserWarning, match="asks to turn while the character stands at rest") as caught:
        controller.step(90, "walk", rest=True)
        controller.step(180, "walk", rest=True)
    assert len([w for w in caught if "stands at rest" in str(w.message)]) == 1
    assert sum("stands at rest" in w for w in controller.motion.report["warnings"]) == 1
    stood = len(controller.motion)
    # Asked to move, it starts off from rest (the graph has no way on from the frame it holds): one
    # step blends that frame into a lead-in that walks off, without a word; the report says when.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        step = controller.step(90, "walk")
    assert not controller.resting and not controller.standing
    assert np.linalg.norm(step.positions[0, 0, [0, 2]] - motion.positions[-1, 0, [0, 2]]) < 0.01
    while len(controller.motion) < len(motion) + 6 * fps:
        controller.step(90, "walk")
    after = controller.motion
    assert np.linalg.norm(after.positions[-1, 0, [0, 2]] - motion.positions[-1, 0, [0, 2]]) > 2
    starts = after.report["starts"]
    assert len(starts) == 1 and starts[0]["at_s"] == stood / fps and starts[0]["rms_cm"] > 0, starts
    assert after.report["rests"] == [rest] and after.report["rest"] == rest
    assert after.report["transitions"] >= motion.report["transitions"] + 1
    assert after.report["foot_slide"]["same_frames"]["steps"] > 0
    with pytest.raises(TypeError):
        controller.step(0, "walk", rest=1)  # True or False, as the CLI and the studio take it
    # A stop the graph can hardly play is rest too, said once; asked of the controller itself it only
    # picks where it starts (a step's own tag is what it plays), and says nothing.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        graph.controller(heading_deg=0, tag="stop")
    other = graph.controller(heading_deg=0, tag="walk")
    with pytest.warns(UserWarning, match="comes to rest instead"):
        other.step(0, "stop")
    while other.rest_s is None and len(other.motion) < 10 * fps:
        other.step(0, "stop")
    assert other.rest_s is not None


def test_rest_taken_back_on_the_way_equals_the_cli(cli, graph_file, graph, tmp_path):
    # Asked to rest at 2 s and to walk on at 3.5 s, before it stands: it goes on at once (the rest
    # is none), frame for frame as the CLI's steer plays the same controls.
    controls = [{"at_s": 0, "heading_deg": 0, "tag": "walk"}, {"at_s": 2, "rest": True},
                {"at_s": 3.5, "rest": False}]
    (tmp_path / "controls.json").write_text(json.dumps({"duration_s": 6, "controls": controls}))
    cli("steer", graph_file, "--script", tmp_path / "controls.json", "-o", tmp_path / "cli.json",
        "--report", tmp_path / "cli-report.json")
    fps = graph.fps
    controller = graph.controller(heading_deg=0, tag="walk")
    resting = []
    while len(controller.motion) < 6 * fps:
        t = len(controller.motion) / fps
        controller.step(0, "walk", rest=2 <= t < 3.5)
        resting.append(controller.resting)
    assert any(resting) and not controller.resting and controller.rest_s is None
    motion, want = controller.motion, read_json(tmp_path / "cli.json")
    total = len(want["positions"])
    assert np.max(np.abs(motion.positions[:total] - np.asarray(want["positions"]))) <= 1e-6
    report = read_json(tmp_path / "cli-report.json")
    assert motion.report["rests"] == report["rests"] == [] and motion.report["rest"] is None
    assert motion.report["starts"] == report["starts"]
    back = report["rests_taken_back_s"]
    assert motion.report["rests_taken_back_s"] == back and len(back) == 1 and 3.5 <= back[0] < 4, back
    assert all(start["under_way"] for start in report["starts"]), report["starts"]
    assert report["controls"][1]["rest_taken_back"], report["controls"]
    # Walking on: 0.8 m or more in the 1.5 s after it was asked.
    root = motion.positions[:, 0, [0, 2]]
    asked = int(np.ceil(3.5 * fps))
    assert np.linalg.norm(root[asked + int(1.5 * fps)] - root[asked]) > 0.8


def test_path_to_rest_equals_the_cli(cli, graph_file, graph, tmp_path):
    cli("path", graph_file, "--shape", "circle:4", "--rest-at-end", "-o", tmp_path / "cli.json",
        "--report", tmp_path / "cli-report.json")
    motion = graph.path(shape="circle:4", rest_at_end=True)
    assert_positions_equal(motion, read_json(tmp_path / "cli.json"))
    rest = motion.report["rest"]
    assert rest == read_json(tmp_path / "cli-report.json")["rest"] and rest["clip"].startswith("16_")
    assert graph.path(shape="circle:4").report["rest"] is None


def test_a_step_plays_decisions_until_min_frames(graph):
    # One step of min_frames plays what single steps with the same controls play, decision by
    # decision, until it has that many frames (each decision ends with a whole edge).
    many, one = graph.controller(heading_deg=90, tag="walk"), graph.controller(heading_deg=90, tag="walk")
    got = many.step(90, "walk", min_frames=60)
    assert len(got) >= 60
    while len(one.motion) < len(got):
        one.step(90, "walk")
    assert len(one.motion) == len(got)
    np.testing.assert_array_equal(got.positions, one.motion.positions)
    np.testing.assert_array_equal(got.contacts, one.motion.contacts)
    assert many.motion.report["decisions"] == one.motion.report["decisions"] > 1
    assert len(many.step(90, "walk")) < 60  # (one decision by default)
    for bad in (0, 3601):
        with pytest.raises(ValueError, match="min_frames must be from 1 to 3600"):
            many.step(90, "walk", min_frames=bad)


def test_numbers_of_walks_paths_and_steps_are_not_true_or_false(graph, graph_file):
    # pybind11 took True for node 1 and False for 0 (graph.walk(True, 5)), a heading of 1 degree.
    controller = graph.controller()
    calls = [lambda: graph.walk(True, 5), lambda: graph.walk(0, False),
             lambda: graph.path(points=[(True, False), (0, -5)]),
             lambda: graph.controller(heading_deg=True), lambda: graph.controller(at=(0, True)),
             lambda: controller.step(True), lambda: controller.step(0, min_frames=True),
             lambda: mg.load_graph(str(graph_file), skeleton=True), lambda: graph.walk(np.True_, 5)]
    for call in calls:
        with pytest.raises(TypeError, match="a number is expected, not (True|False)"):
            call()
    with pytest.raises(TypeError, match="keyword argument 'horizon' cannot be a bool"):
        graph.controller(horizon=np.True_)  # a keyword option: named
    assert len(controller.motion) == 0  # no step was taken
    assert len(graph.walk(1, 5)) > 0
    assert len(controller.step(0, min_frames=2)) >= 2
    with pytest.raises(TypeError, match=r"step\(\) got an unexpected keyword argument 'min_frame'"):
        controller.step(0, min_frame=2)
    # A skeleton index below -1 (the first clip's) is none.
    with pytest.raises(ValueError, match="skeleton must be -1"):
        mg.load_graph(str(graph_file), skeleton=-2)
    # An int past C's int is said as such (pybind11 answered with every signature of the function).
    for call in (lambda: graph.walk(2**40, 5), lambda: graph.walk(0, -2**31 - 1),
                 lambda: controller.step(0, min_frames=2**63), lambda: mg.load_graph(str(graph_file), skeleton=2**31)):
        with pytest.raises(ValueError, match=r"an integer from -2147483648 to 2147483647 is expected, not -?\d+$"):
            call()


def test_steering_goes_where_it_is_told(graph):
    controller = graph.controller(heading_deg=90, tag="walk")
    while len(controller.motion) < 5 * graph.fps:
        controller.step(90, "walk")
    root = controller.motion.positions[:, 0, :]
    last = root[-3 * int(graph.fps):]
    # East is +x: over the last three seconds the root moves east, within 10 degrees. (As the graph
    # plays it, without the heading edit, a walk held to a heading weaves about it, on subject 16
    # by 0.3-0.7 m either side over 4-5 s: a single second can head 45 degrees off.)
    dx, dz = last[-1, 0] - last[0, 0], last[-1, 2] - last[0, 2]
    assert dx > 1.5 and abs(dz) < 0.18 * dx, (dx, dz)


def test_heading_edit_options_reach_the_controller(cli, graph_file, graph, tmp_path):
    (tmp_path / "controls.json").write_text(json.dumps({"duration_s": 4, "controls": [{"at_s": 0, "heading_deg": 60}]}))
    total = round(4 * graph.fps)
    played = {}
    for name, args, kwargs in (("default", [], {}), ("off", ["--edit-max-turn", 0], dict(edit_max_turn=0)),
                               ("slow", ["--edit-turn-distance", 3], dict(edit_turn_distance=3)),
                               ("travel", ["--edit-hold", "travel"], dict(edit_hold="travel"))):
        cli("steer", graph_file, "--script", tmp_path / "controls.json", "-o", tmp_path / f"{name}.json",
            "--report", tmp_path / f"{name}-r.json", *args)
        controller = graph.controller(heading_deg=60, **kwargs)
        while len(controller.motion) < total:
            controller.step(60)
        want = np.asarray(read_json(tmp_path / f"{name}.json")["positions"])
        assert np.max(np.abs(controller.motion.positions[:total] - want)) <= 1e-6, name
        played[name] = want
        report = read_json(tmp_path / f"{name}-r.json")["heading_edit"]
        assert (report["added_turn_deg"] == 0) == (name == "off"), (name, report)
        assert report["hold"] == ("travel" if name == "travel" else "facing"), (name, report)
        assert (report["travel_share"] > 0.5) == (name == "travel"), (name, report)
    assert np.max(np.abs(played["default"] - played["off"])) > 0.05
    assert np.max(np.abs(played["default"] - played["slow"])) > 0.01
    assert np.max(np.abs(played["default"] - played["travel"])) > 0.01
    with pytest.raises(mg.Error):
        graph.controller(edit_turn_distance=0)
    with pytest.raises(mg.Error, match="--edit-hold"):
        graph.controller(edit_hold="sideways")


@pytest.mark.parametrize("cli_args, call", [
    (["--shape", "line:5", "--segment", "swim:0-5"], lambda g: g.path(shape="line:5", segments=["swim:0-5"])),
    (["--shape", "line:5", "--segment", "walk0-5"], lambda g: g.path(shape="line:5", segments=["walk0-5"])),
    (["--shape", "wiggle:5"], lambda g: g.path(shape="wiggle:5")),
    (["--shape", "line:5", "--horizon", "-1"], lambda g: g.path(shape="line:5", horizon=-1)),
    (["--shape", "line:5", "--tag-lookahead", "1.5"], lambda g: g.path(shape="line:5", tag_lookahead=1.5)),
])
def test_path_errors_raise_the_cli_message(cli, graph_file, graph, tmp_path, cli_args, call):
    want = cli_error(cli("path", graph_file, *cli_args, "-o", tmp_path / "o.json", check=False))
    with pytest.raises(mg.Error) as raised:
        call(graph)
    assert str(raised.value) == want


def test_save_says_what_it_cannot_do(graph, tmp_path):
    """Options the format does not take warn (they were dropped silently); the CLI's pairing of
    --root-motion-smoothing with --root-motion holds; a motion of no frames is refused."""
    motion = graph.path(shape="line:5")
    with pytest.warns(UserWarning, match=r"output_scale is for \.bvh; \.glb is written in metres"):
        motion.save(tmp_path / "m.glb", output_scale=100)
    with pytest.warns(UserWarning, match=r"figure=False is for \.glb, \.gltf or \.fbx; \.bvh has no stick figure"):
        motion.save(tmp_path / "m.bvh", figure=False)
    with pytest.raises(ValueError, match="root_motion_smoothing needs root_motion=True"):
        motion.save(tmp_path / "m2.bvh", root_motion_smoothing=1.0)
    assert not (tmp_path / "m2.bvh").exists()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        motion.save(tmp_path / "m3.bvh", output_scale=100)
        motion.save(tmp_path / "m3.glb", root_motion=True, root_motion_smoothing=0.25, figure=False)
    with pytest.raises(ValueError, match="the motion has no frames"):
        graph.controller().motion.save(tmp_path / "empty.bvh")
    # As save_animations says it (it was a motiongraph.Error), and no file.
    with pytest.raises(ValueError, match=r"motions\[1\] has no frames"):
        mg.save_animations(tmp_path / "set.glb", [motion, graph.controller().motion])
    assert not (tmp_path / "set.glb").exists()


def test_path_progress_every_two_seconds_and_its_exception_stops_the_search(graph):
    """progress= hears how far along a long path the searches have come, every 2 s, further each
    time; an exception it raises stops the search and is raised (as build's progress)."""
    lines = []

    def heard(line):
        lines.append(line)
        if len(lines) == 2:
            raise RuntimeError("enough")
    with pytest.raises(RuntimeError, match="enough"):
        graph.path(shape="line:100000", progress=heard)
    assert len(lines) == 2
    got = [re.fullmatch(r"path: ([\d.]+) m of 100000\.0 m along it \(search 1 of the whole path\) in ([\d.]+) s", l)
           for l in lines]
    assert all(got), lines
    assert float(got[0][1]) < float(got[1][1]) and 2 <= float(got[0][2]) < float(got[1][2]), lines
    assert graph.path(shape="line:5", progress=lines.append).report["reached_end"]
    assert len(lines) == 2  # done within 2 s: not a word
    with pytest.raises(TypeError, match=r"path\(\): progress must be callable"):
        graph.path(shape="line:5", progress=3)  # said though the search would not last 2 s


def test_a_path_is_one_of_points_shape_and_file(graph, tmp_path):
    """Said in the keywords Python takes (the CLI says "--path and --shape")."""
    line = [(0, 0), (0, -5)]
    for kwargs in ({}, {"shape": "line:5", "points": line}, {"shape": "line:5", "file": tmp_path / "p.json"}):
        with pytest.raises(ValueError, match=r"path\(\) takes exactly one of points, shape and file"):
            graph.path(**kwargs)
    for points in ([], [(0, 0)]):
        with pytest.raises(ValueError, match=f"a path needs at least two points, not {len(points)}"):
            graph.path(points=points)


def test_errors_name_the_graph_file_as_the_cli_does(cli, graph_file, graph, tmp_path):
    nodes = graph.node_count
    want = cli_error(cli("walk", graph_file, "--from", 0, "--to", nodes, "-o", tmp_path / "o.json", check=False))
    with pytest.raises(mg.Error) as raised:
        graph.walk(0, nodes)
    assert str(raised.value) == want
    want = cli_error(cli("walk", graph_file, "--from", 0, "--to", 1, "--cost", "cheap", "-o", tmp_path / "o.json",
                         check=False))
    with pytest.raises(mg.Error) as raised:
        graph.walk(0, 1, cost="cheap")
    assert str(raised.value) == want
    want = cli_error(cli("path", graph_file, "--shape", "line:5", "-o", tmp_path / "o.txt", check=False))
    with pytest.raises(mg.Error) as raised:
        graph.path(shape="line:5").save(str(tmp_path / "o.txt"))
    assert str(raised.value) == want
    with pytest.raises(mg.Error, match="'swim' is not a motion tag"):
        graph.controller(tag="swim")
    with pytest.raises(TypeError, match="unexpected keyword argument 'horizn'"):
        graph.path(shape="line:5", horizn=2)


def test_path_releases_the_gil(graph):
    assert_releases_the_gil(lambda: graph.path(shape="figure8:4", segments=["walk:0-25", "run:25-51"]))


@pytest.mark.parametrize("work", [lambda g: g.path(shape="line:100000"),
                                  lambda g: g.walk(0, 5, min_frames=50000, max_expansions=10**12)],
                         ids=["path", "walk"])
def test_ctrl_c_stops_a_long_search(graph, work):
    # A path of 100 km and a walk searched without end: stopped only by Ctrl-C (as it comes, the
    # signal's flag set a moment after the search began, Python's handler left to the main thread).
    import _thread
    import threading

    timer = threading.Timer(0.3, _thread.interrupt_main)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            work(graph)
    finally:
        timer.cancel()


def test_bridge_penalty_reaches_the_steering_search(cli, graph_file, graph, tmp_path):
    # Asked for no motion type, subject 16's steering turns through bridges when they cost as any
    # transition (--bridge-penalty 0) and without them by default. Which turns a graph takes
    # through bridges is its own (measured: 2 bridges in each of the first three 8 s scripts on
    # the graph of RMS 3.46 cm, none in the fourth, which took 3 on that of 2.65 cm), so four
    # scripts are run and the bridges summed; Python's controller plays each exactly as the
    # CLI's. Without the heading edit: with it the walks turn enough that these scripts take no
    # bridge either way.
    scripts = [[(0, 0), (2, 60), (5, 270)], [(0, 0), (1, 90), (4, 0)], [(0, 0), (1, 135), (4, 0)],
               [(0, 0), (2, 180), (5, 0)]]
    fps = graph.fps
    total = round(8 * fps)
    bridges = {0: 0, 30: 0}
    for i, script in enumerate(scripts):
        controls = [{"at_s": at, "heading_deg": heading} for at, heading in script]
        (tmp_path / "controls.json").write_text(json.dumps({"duration_s": 8, "controls": controls}))
        for penalty, kwargs in ((0, dict(bridge_penalty=0)), (30, {})):
            out = tmp_path / f"cli{i}-{penalty}.json"
            cli("steer", graph_file, "--script", tmp_path / "controls.json", "--bridge-penalty", penalty, "-o", out,
                "--report", tmp_path / "r.json", "--edit-max-turn", 0)
            bridges[penalty] += read_json(tmp_path / "r.json")["bridges"]
            controller = graph.controller(heading_deg=0, edit_max_turn=0, **kwargs)
            while len(controller.motion) < total:
                heading = [c for c in controls if c["at_s"] <= len(controller.motion) / fps][-1]["heading_deg"]
                controller.step(heading)
            want = read_json(out)
            assert np.max(np.abs(controller.motion.positions[:total] - np.asarray(want["positions"]))) <= 1e-6
    assert bridges[0] > 0 and bridges[30] == 0, bridges


def test_warnings_made_errors_raise_the_warning(data):
    """Under warnings.simplefilter("error") a warning is raised as its UserWarning (not a
    SystemError): the build's, and the clean-up's on path, walk and the controller."""
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ankles_at_hips = mg.build(str(data / "cmu/16"), no_cache=True, feet="lhipjoint,,rhipjoint,",
                                  threshold="4cm", no_path_check=True)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(UserWarning, match="the graph keeps 2 % of the frames"):
            mg.build(str(data / "cmu/16"), no_cache=True, threshold="1cm", no_path_check=True)
        for call in (lambda: ankles_at_hips.path(shape="line:5"), lambda: ankles_at_hips.walk(0, 5),
                     lambda: ankles_at_hips.controller()):
            with pytest.raises(UserWarning, match="the clean-up needs a knee and a hip above ankle 'lhipjoint'"):
                call()


def test_threads_sharing_a_controller_take_turns(graph):
    """Steps of one controller from several threads run one at a time: every frame each returned
    is in the motion, in the order the steps ran, and nothing is lost or torn."""
    import threading
    controller = graph.controller(heading_deg=0, tag="walk")
    steps, errors, lock = [], [], threading.Lock()

    def steer(k):
        try:
            for i in range(12):
                step = controller.step((i * 37 * k) % 360, ["walk", "run", None][i % 3])
                with lock:
                    steps.append(step.positions)
        except Exception as e:  # noqa: BLE001 -- any failure fails the test below
            errors.append(e)

    threads = [threading.Thread(target=steer, args=(k,)) for k in range(1, 5)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors
    assert len(steps) == 48
    everything = controller.motion.positions
    assert len(everything) == sum(len(s) for s in steps)
    # The steps appended in the order their lock was taken, which each thread's list order follows
    # but the shared list may not: each step's frames are a run of the whole motion's.
    for s in steps:
        hits = [f for f in range(len(everything) - len(s) + 1) if np.array_equal(everything[f], s[0])]
        assert any(np.array_equal(everything[f:f + len(s)], s) for f in hits)


def test_controller_headings_and_start_must_be_finite(graph):
    with pytest.raises(mg.Error, match="the start position is not a finite point"):
        graph.controller(at=(float("nan"), 0.0))
    with pytest.raises(ValueError, match="heading_deg must be finite"):
        graph.controller(heading_deg=float("inf"))
    controller = graph.controller()
    with pytest.raises(ValueError, match="heading_deg must be finite"):
        controller.step(float("nan"), "walk")
    assert np.isfinite(controller.step(90, "walk").positions).all()


def test_path_segments_may_be_none(graph):
    with_none = graph.path(shape="line:5", segments=None)
    assert np.array_equal(with_none.positions, graph.path(shape="line:5").positions)
