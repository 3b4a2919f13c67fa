"""load_clip() and Motion: the same clip as the CLI's convert, arrays without copies."""
import json
import os
import subprocess

import numpy as np
import pytest

import motiongraph as mg
from conftest import assert_bare_glb, assert_positions_equal, cli_error, glb_json, read_json


@pytest.mark.parametrize("fps", [None, 30.0])
def test_positions_equal_the_cli(cli, data, tmp_path, fps):
    amc = data / "cmu/16/16_15.amc"
    args = ["--fps", fps] if fps else []
    cli("convert", amc, "-o", tmp_path / "cli.json", *args)
    clip = mg.load_clip(str(amc), fps=fps)
    assert_positions_equal(clip, read_json(tmp_path / "cli.json"))
    # What save() writes is the CLI's file, byte for byte, in every format (glTF names its
    # animation as the file: the same name in two folders).
    (tmp_path / "cli").mkdir()
    (tmp_path / "py").mkdir()
    cli("convert", amc, "-o", tmp_path / "cli.bvh", "-o", tmp_path / "cli" / "walk.glb", "-o",
        tmp_path / "cli" / "walk.fbx", "-o", tmp_path / "cli" / "walk.gltf", *args)
    for ext in ("json", "bvh"):
        clip.save(str(tmp_path / f"py.{ext}"))
        assert (tmp_path / f"py.{ext}").read_bytes() == (tmp_path / f"cli.{ext}").read_bytes()
    clip.save(str(tmp_path / "py" / "walk.glb"))
    assert (tmp_path / "py" / "walk.glb").read_bytes() == (tmp_path / "cli" / "walk.glb").read_bytes()
    assert (tmp_path / "py" / "walk.glb").read_bytes()[:4] == b"glTF"
    # name= names the animation (the CLI's is the file's: a motion renamed keeps its name so); on a
    # format with no animation name it is said.
    clip.save(str(tmp_path / "py" / "named.gltf"), name="Gehen nach Osten")
    assert json.loads((tmp_path / "py" / "named.gltf").read_text())["animations"][0]["name"] == "Gehen nach Osten"
    with pytest.warns(UserWarning, match="name is for .glb, .gltf or .fbx; .bvh has no animation name"):
        clip.save(str(tmp_path / "named.bvh"), name="walk")
    with pytest.raises(ValueError, match="name must not be empty"):
        clip.save(str(tmp_path / "py" / "empty-name.glb"), name="")
    # .gltf: the same model as one JSON file, its buffer a base64 data URI.
    clip.save(str(tmp_path / "py" / "walk.gltf"))
    assert (tmp_path / "py" / "walk.gltf").read_bytes() == (tmp_path / "cli" / "walk.gltf").read_bytes()
    text = json.loads((tmp_path / "py" / "walk.gltf").read_text())
    assert text["asset"]["version"] == "2.0"
    assert text["buffers"][0]["uri"].startswith("data:application/octet-stream;base64,")
    assert text["animations"][0]["name"] == "walk"
    clip.save(str(tmp_path / "py" / "walk.fbx"))
    assert (tmp_path / "py" / "walk.fbx").read_bytes() == (tmp_path / "cli" / "walk.fbx").read_bytes()
    assert (tmp_path / "py" / "walk.fbx").read_bytes()[:21] == b"Kaydara FBX Binary  \0"
    cli("convert", amc, "--root-motion", "-o", tmp_path / "cli-rm.json", *args)
    clip.save(str(tmp_path / "py-rm.json"), root_motion=True)
    assert (tmp_path / "py-rm.json").read_bytes() == (tmp_path / "cli-rm.json").read_bytes()
    # In centimetres, and glTF without its stick figure: the CLI's --output-scale and --no-figure.
    cli("convert", amc, "--output-scale", 100, "--no-figure", "-o", tmp_path / "cli-cm.bvh", "-o",
        tmp_path / "cli" / "bare.glb", *args)
    clip.save(str(tmp_path / "py-cm.bvh"), output_scale=100)
    assert (tmp_path / "py-cm.bvh").read_bytes() == (tmp_path / "cli-cm.bvh").read_bytes()
    clip.save(str(tmp_path / "py" / "bare.glb"), figure=False)
    assert (tmp_path / "py" / "bare.glb").read_bytes() == (tmp_path / "cli" / "bare.glb").read_bytes()
    assert_bare_glb(tmp_path / "py" / "bare.glb", tmp_path / "py" / "walk.glb")
    metres, centimetres = (offsets(tmp_path / name) for name in ("py.bvh", "py-cm.bvh"))
    assert len(metres) == len(centimetres) > 20
    np.testing.assert_allclose(centimetres, 100 * metres, atol=1e-6 * 100)
    with pytest.raises(mg.Error, match="BVH output scale must lie between 1e-06 and 1e\\+06 units per metre, not 0"):
        clip.save(str(tmp_path / "zero.bvh"), output_scale=0)
    assert not (tmp_path / "zero.bvh").exists()


def test_animation_set_equals_the_cli(cli, data, tmp_path):
    clips = [data / "cmu/16/16_15.amc", data / "cmu/16/16_35.amc"]
    cli("convert", *clips, "--fps", 30, "-o", tmp_path / "cli.glb")
    cli("convert", *clips, "--fps", 30, "--root-motion", "--no-figure", "-o", tmp_path / "cli-rm.glb")
    motions = [mg.load_clip(str(c), fps=30) for c in clips]
    mg.save_animations(str(tmp_path / "py.glb"), motions)
    assert (tmp_path / "py.glb").read_bytes() == (tmp_path / "cli.glb").read_bytes()
    mg.save_animations(str(tmp_path / "py-rm.glb"), motions, root_motion=True, figure=False)
    assert (tmp_path / "py-rm.glb").read_bytes() == (tmp_path / "cli-rm.glb").read_bytes()
    gltf = glb_json(tmp_path / "py.glb")
    assert [a["name"] for a in gltf["animations"]] == ["16_15", "16_35"]
    mg.save_animations(str(tmp_path / "named.glb"), motions + motions[:1], names=["walk", "jog", "walk"])
    assert [a["name"] for a in glb_json(tmp_path / "named.glb")["animations"]] == ["walk", "jog", "walk_2"]
    # Another rig (a converter's BVH of the same capture), names that do not match the motions,
    # another format: errors, and no file.
    other = mg.load_clip(str(data / "bvh/16_01.bvh"))
    with pytest.raises(mg.Error, match="its rig is not 16_15's .*one .glb holds one skeleton"):
        mg.save_animations(str(tmp_path / "mixed.glb"), [motions[0], other])
    # And read back: each animation of the set is its clip (float32 keys).
    back = [mg.load_clip(str(tmp_path / "py.glb"), animation=name) for name in ("16_15", "16_35")]
    for clip, read in zip(motions, back):
        assert read.name == f"py:{clip.name}" and read.fps == 30 and len(read) == len(clip)
        order = [read.joint_names.index(n) for n in clip.joint_names]
        np.testing.assert_allclose(read.positions[:, order], clip.positions, atol=2e-5)
    # The same set as FBX: the CLI's file, a stack each, read back to each clip.
    cli("convert", *clips, "--fps", 30, "-o", tmp_path / "cli.fbx")
    mg.save_animations(str(tmp_path / "py.fbx"), motions)
    assert (tmp_path / "py.fbx").read_bytes() == (tmp_path / "cli.fbx").read_bytes()
    for clip in motions:
        read = mg.load_clip(str(tmp_path / "py.fbx"), animation=clip.name)
        assert read.name == f"py:{clip.name}" and read.fps == 30 and len(read) == len(clip)
        order = [read.joint_names.index(n) for n in clip.joint_names]
        np.testing.assert_allclose(read.positions[:, order], clip.positions, atol=2e-5)
    # A message naming a joint whose name is not UTF-8 (Latin-1) is still motiongraph.Error.
    latin1 = tmp_path / "latin1.bvh"
    latin1.write_bytes((data / "bvh/16_01.bvh").read_bytes().replace(b"lfemur", b"Oberschenkel\xfc"))
    with pytest.raises(mg.Error, match="'Oberschenkel\ufffd' here"):
        mg.save_animations(str(tmp_path / "mixed.glb"), [mg.load_clip(str(data / "bvh/16_01.bvh")),
                                                         mg.load_clip(str(latin1))])
    with pytest.raises(ValueError, match="names: 1 given for 2 motions"):
        mg.save_animations(str(tmp_path / "mixed.glb"), motions, names=["walk"])
    with pytest.raises(mg.Error, match="several motions go into a .glb, .gltf or .fbx only"):
        mg.save_animations(str(tmp_path / "set.bvh"), motions)
    assert not (tmp_path / "mixed.glb").exists() and not (tmp_path / "set.bvh").exists()


def offsets(bvh):
    """Every OFFSET of a BVH file, in its own units."""
    return np.array([[float(v) for v in line.split()[1:4]] for line in bvh.read_text().splitlines()
                     if line.strip().startswith("OFFSET")])


@pytest.mark.parametrize("path, input_fps, fps", [("bvh/16_01.bvh", 0.0, None), ("cmu/16/16_15.amc", 30.0, None),
                                                   ("cmu/16/16_15.amc", 30.0, 60.0), ("bvh/07_12.bvh", 0.0, None),
                                                   ("cmu/16/16_15.amc", 0.0, None)])
def test_doubts_are_the_cli_info_s(cli, data, path, input_fps, fps):
    # A clock 4x slow (by its flights, by its walk), a floor offset, and a clip that looks right:
    # info's doubts. Resampled after reading, the clip is judged at its new rate and the phrase
    # names the rate it was read at.
    args = ["--input-fps", input_fps] if input_fps else []
    info = json.loads(cli("info", "--json", *args, data / path).stdout)[0]
    clip = mg.load_clip(str(data / path), input_fps=input_fps, fps=fps)
    if fps is None:
        assert clip.doubts == info["doubts"]
    if path != "cmu/16/16_15.amc" or input_fps:
        assert clip.doubts, path
    if input_fps:
        assert "its frame rate as read, 30 fps, is likely about 4" in clip.doubts[0], clip.doubts


def test_glitches_are_the_cli_info_s(cli, data, tmp_path):
    # 131_01 with its right shoulder turned 100 degrees in the file's frame 301 alone: a limb out
    # and back, two glitches (after frames 300 and 301), as info finds them; a library cuts the
    # clip there, dropping that frame.
    lines = (data / "bvh/131_01.bvh").read_text().split("\n")
    channels, column = 0, None
    for line in lines:
        words = line.split()
        if words[:1] == ["JOINT"] and words[1] == "RightShoulder":
            column = channels + 2   # its third channel (Z Y X rotation order): X
        if words[:1] == ["CHANNELS"]:
            channels += int(words[1])
    first = next(i for i, line in enumerate(lines) if line.startswith("Frame Time")) + 1
    values = lines[first + 300].split()
    values[column] = str(float(values[column]) + 100.0)
    lines[first + 300] = " ".join(values)
    bvh = tmp_path / "lost.bvh"
    bvh.write_text("\n".join(lines))
    info = json.loads(cli("info", "--json", bvh).stdout)[0]["capture_glitches"]
    clip = mg.load_clip(str(bvh))
    assert [g["frame"] for g in clip.glitches] == [300, 301], clip.glitches
    assert clip.glitches == info["glitches"] and info["parts"] == 2 and info["dropped_frames"] == 1, info
    assert abs(clip.glitches[0]["seconds"] - 300 / 120) < 1e-9 and clip.glitches[0]["jump_m"] >= 0.2   # lands on frame 301
    assert mg.load_clip(str(bvh), keep_rest_frames=True).glitches == []
    assert mg.load_clip(str(data / "bvh/131_01.bvh")).glitches == []
    lib = mg.load_library(str(bvh), fps=120, mirror=False)  # its walk turns one way: as read
    assert [c.name for c in lib.clips] == ["lost", "lost_part2"]
    assert len(lib.clips[0]) + len(lib.clips[1]) == len(clip) - 1


def test_contacts_of_a_clip_and_feet_named(cli, data, tmp_path):
    bvh = data / "bvh/16_01.bvh"
    cli("convert", bvh, "-o", tmp_path / "cli.json")
    want = read_json(tmp_path / "cli.json")["contacts"]
    clip = mg.load_clip(str(bvh))
    assert clip.foot_joints == want["joints"] == ["lfoot", "ltoes", "rfoot", "rtoes"]
    np.testing.assert_array_equal(clip.contacts, np.array(want["planted"], dtype=bool))
    # A rig whose feet the finder does not know: no contacts, and none in its JSON, until named.
    renamed = tmp_path / "pes.bvh"
    renamed.write_text(bvh.read_text().replace("lfoot", "lpes").replace("rfoot", "rpes"))
    unknown = mg.load_clip(str(renamed))
    assert unknown.foot_joints is None and unknown.contacts is None
    unknown.save(str(tmp_path / "unknown.json"))
    assert "contacts" not in read_json(tmp_path / "unknown.json")
    named = mg.load_clip(str(renamed), feet="lpes,,rpes,")
    assert named.foot_joints == ["lpes", "ltoes", "rpes", "rtoes"]
    np.testing.assert_array_equal(named.contacts, clip.contacts)
    named.save(str(tmp_path / "named.json"))
    assert read_json(tmp_path / "named.json")["contacts"]["planted"] == want["planted"]
    # Resampled, the contacts are the resampled motion's: one row a frame.
    assert mg.load_clip(str(bvh), fps=30).contacts.shape == (len(mg.load_clip(str(bvh), fps=30)), 4)
    with pytest.raises(ValueError, match="feet: .*four comma-separated joint names"):
        mg.load_clip(str(bvh), feet="lfoot")
    with pytest.raises(mg.Error, match="no joint named 'LeftAnkle'"):
        mg.load_clip(str(bvh), feet="LeftAnkle,,,")


def test_bvh_with_scale_equals_the_cli(cli, data, tmp_path):
    cli("convert", data / "cmu/16/16_15.amc", "-o", tmp_path / "m.bvh")
    cli("convert", tmp_path / "m.bvh", "--scale", 0.5, "-o", tmp_path / "cli.json")
    clip = mg.load_clip(str(tmp_path / "m.bvh"), scale=0.5)
    assert_positions_equal(clip, read_json(tmp_path / "cli.json"))


def test_up_axis_turns_a_bvh_as_told(cli, data, tmp_path):
    cli("convert", data / "cmu/16/16_15.amc", "-o", tmp_path / "m.bvh")
    found = mg.load_clip(str(tmp_path / "m.bvh"))
    y = np.asarray(mg.load_clip(str(tmp_path / "m.bvh"), up_axis="y").positions)
    np.testing.assert_array_equal(np.asarray(found.positions), y)  # the file stands in y
    # Told z, the file's +z is turned to +y and its +y to -z: (x, y, z) -> (x, z, -y).
    z = np.asarray(mg.load_clip(str(tmp_path / "m.bvh"), up_axis="Z").positions)
    np.testing.assert_allclose(z, np.stack([y[..., 0], y[..., 2], -y[..., 1]], axis=-1), atol=1e-9)
    with pytest.raises(ValueError, match="up_axis must be 'y' or 'z'"):
        mg.load_clip(str(tmp_path / "m.bvh"), up_axis="x")


def _in_place(text):
    """A BVH's text with its root's Xposition and Zposition zeroed in every frame (an "in place" export)."""
    lines = text.splitlines()
    channels = next(line.split()[2:] for line in lines if "CHANNELS" in line)
    x, z = channels.index("Xposition"), channels.index("Zposition")
    start = next(i for i, line in enumerate(lines) if line.strip().startswith("Frame Time")) + 1
    for i in range(start, len(lines)):
        values = lines[i].split()
        if values:
            values[x] = values[z] = "0"
            lines[i] = " ".join(values)
    return "\n".join(lines) + "\n"


def test_travel_of_a_clip_in_place(cli, data, tmp_path):
    cli("convert", data / "cmu/16/16_15.amc", "-o", tmp_path / "m.bvh")
    (tmp_path / "in_place.bvh").write_text(_in_place((tmp_path / "m.bvh").read_text()))
    capture = np.asarray(mg.load_clip(str(tmp_path / "m.bvh")).positions)[:, 0]
    as_read = np.asarray(mg.load_clip(str(tmp_path / "in_place.bvh"), travel="root").positions)[:, 0]
    recovered = np.asarray(mg.load_clip(str(tmp_path / "in_place.bvh")).positions)[:, 0]
    span = lambda root: np.linalg.norm((root[-1] - root[0])[[0, 2]])
    assert span(as_read) < 0.2
    assert 0.9 * span(capture) < span(recovered) < 1.05 * span(capture), (span(recovered), span(capture))
    np.testing.assert_array_equal(recovered[:, 1], as_read[:, 1])  # heights as read
    # Asked for the feet on the capture itself: a few per cent of its travel change at most.
    feet = np.asarray(mg.load_clip(str(tmp_path / "m.bvh"), travel="FEET").positions)[:, 0]
    assert abs(span(feet) - span(capture)) < 0.1 * span(capture)
    with pytest.raises(ValueError, match="travel must be 'auto', 'root' or 'feet'"):
        mg.load_clip(str(tmp_path / "m.bvh"), travel="hips")


def test_arrays_are_views_of_the_clip(data):
    clip = mg.load_clip(str(data / "cmu/16/16_15.amc"), asf=str(data / "cmu/16/16.asf"))
    positions, rotations = clip.positions, clip.rotations
    frames, joints = len(clip), len(clip.joint_names)
    assert positions.shape == (frames, joints, 3) and positions.dtype == np.float64
    assert rotations.shape == (frames, joints, 4)
    # No copies: every access is a view of the same memory, which the clip owns.
    assert not positions.flags.owndata and np.shares_memory(positions, clip.positions)
    assert not rotations.flags.owndata and np.shares_memory(rotations, clip.rotations)
    assert not positions.flags.writeable
    np.testing.assert_allclose(np.linalg.norm(rotations, axis=2), 1.0, atol=1e-9)
    assert clip.parents[0] == -1 and all(p < j for j, p in enumerate(clip.parents))
    assert clip.fps == 120.0
    del clip  # the arrays keep it alive
    assert np.isfinite(positions).all()


def test_bad_clip_raises_the_cli_message(cli, data, tmp_path):
    bad = tmp_path / "bad.bvh"
    bad.write_text("HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0\n")
    want = cli_error(cli("convert", bad, "-o", tmp_path / "x.json", check=False))
    with pytest.raises(mg.Error) as raised:
        mg.load_clip(str(bad))
    assert str(raised.value) == want
    clip = mg.load_clip(str(data / "cmu/16/16_15.amc"))
    want = cli_error(cli("convert", data / "cmu/16/16_15.amc", "-o", tmp_path / "x.txt", check=False))
    with pytest.raises(mg.Error) as raised:
        clip.save(str(tmp_path / "x.txt"))
    assert str(raised.value) == want


def test_paths_may_be_path_objects(data, tmp_path):
    clip = mg.load_clip(data / "cmu/16/16_15.amc", asf=data / "cmu/16/16.asf")
    assert np.array_equal(clip.positions, mg.load_clip(str(data / "cmu/16/16_15.amc")).positions)
    clip.save(tmp_path / "c.bvh")
    mg.save_animations(tmp_path / "c.glb", [clip])
    assert (tmp_path / "c.bvh").stat().st_size > 0 and (tmp_path / "c.glb").stat().st_size > 0


def test_a_rate_past_what_a_clip_may_hold_raises(data):
    with pytest.raises(mg.Error, match="over the 50 million joint poses a clip may hold"):
        mg.load_clip(data / "cmu/16/16_15.amc", fps=1e6)
    # Below the CLI's least (0.01): no rate, not a clip of one frame.
    with pytest.raises(ValueError, match="fps must be at least 0.01, not 1e-06"):
        mg.load_clip(data / "cmu/16/16_15.amc", fps=1e-6)


def test_missing_clip_raises(tmp_path):
    # Said as missing, not as a skeleton missing beside it.
    for name in ("missing.amc", "missing.bvh"):
        with pytest.raises(mg.Error, match=f"{name}: cannot open: No such file"):
            mg.load_clip(str(tmp_path / name))


def test_fbx_stacks_read_as_the_cli(cli, data, tmp_path):
    # Two clips of subject 16 as one FBX built by FBX's rules (tests/cli/make_test_fbx: z up,
    # inches, pre-rotations, every rotation order), an animation stack each.
    make = os.environ.get("MAKE_TEST_FBX")
    if not make:
        pytest.skip("MAKE_TEST_FBX is not set (run the tests through ctest)")
    fbx = tmp_path / "s16.fbx"
    subprocess.run([make, "--up", "+z", "--unit", "2.54", str(fbx), str(data / "cmu/16/16_15.amc"),
                    str(data / "cmu/16/16_35.amc")], check=True)
    clip = mg.load_clip(str(fbx), animation="16_35")
    assert clip.name == "s16:16_35" and clip.fps == 30
    cli("convert", fbx, "--animation", "16_35", "-o", tmp_path / "cli.json")
    assert_positions_equal(clip, read_json(tmp_path / "cli.json"))
    amc = mg.load_clip(str(data / "cmu/16/16_35.amc"), fps=30)
    order = [clip.joint_names.index(n) for n in amc.joint_names]
    np.testing.assert_allclose(clip.positions[:, order], amc.positions, atol=1e-4)
    with pytest.raises(mg.Error, match="no animation 'swim' \\(the file has 16_15, 16_35\\)"):
        mg.load_clip(str(fbx), animation="swim")


def test_names_that_are_not_utf8(data, tmp_path):
    """A file or folder named in Latin-1 (b"lat\\xe9n"), as bytes or os.fsdecode's str, is read,
    built and written; names from such files (the clip's, a joint's) show the byte as U+FFFD, as
    the JSON reports do, instead of raising UnicodeDecodeError."""
    root = os.fsencode(tmp_path)
    bvh = (data / "bvh/16_01.bvh").read_bytes().replace(b"JOINT lfemur", b"JOINT lf\xe9mur")
    with open(root + b"/lat\xe9n.bvh", "wb") as f:
        f.write(bvh)
    for path in (root + b"/lat\xe9n.bvh", os.fsdecode(root + b"/lat\xe9n.bvh")):
        clip = mg.load_clip(path)
        assert clip.name == "lat\ufffdn" and "lf\ufffdmur" in clip.joint_names and "lat\ufffdn" in repr(clip)
    folder = root + b"/libl\xe9"
    os.mkdir(folder)
    for name in ("16.asf", "16_15.amc", "16_16.amc"):
        with open(folder + b"/" + name.encode(), "wb") as f:
            f.write((data / "cmu/16" / name).read_bytes())
    for given in (folder, os.fsdecode(folder)):
        assert [c.name for c in mg.load_library(given)] == ["16_15", "16_16"]
    graph = mg.build(folder, no_cache=True, no_path_check=True, threshold_quantile=0.2)
    graph.save(folder + b"/g\xe9.mgraph")
    assert graph.name == os.fsdecode(folder + b"/g\xe9.mgraph").encode("utf-8", "surrogateescape").decode(
        "utf-8", "replace")
    clip.save(folder + b"/out\xe9.bvh")
    assert os.path.exists(folder + b"/out\xe9.bvh")


def test_a_motion_made_from_arrays(data, tmp_path):
    """with_frames: a new motion on a clip's skeleton from its arrays as rotations and translations
    give them; the same arrays give the same positions, a turn of the root turns every joint, and
    what it makes saves and reads back as any clip."""
    clip = mg.load_clip(data / "cmu/16/16_15.amc", fps=30)
    assert clip.translated_joints == [0] and clip.translations.shape == (len(clip), 1, 3)
    same = clip.with_frames(clip.rotations, clip.translations)
    assert np.max(np.abs(same.positions - clip.positions)) < 1e-12 and same.name == clip.name
    # A quarter turn about the vertical, of the root's rotation and its place.
    c, s = np.cos(np.pi / 4), np.sin(np.pi / 4)   # half angle
    turn = np.array([0.0, s, 0.0, c])              # (x, y, z, w)

    def times(a, b):  # Hamilton products of (x, y, z, w) quaternions
        ax, ay, az, aw = np.moveaxis(a, -1, 0)
        bx, by, bz, bw = np.moveaxis(b, -1, 0)
        return np.stack([aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
                         aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz], axis=-1)
    rotations = np.array(clip.rotations)
    rotations[:, 0] = times(turn, rotations[:, 0])
    quarter = np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]])  # +90 degrees about y
    turned = clip.with_frames(rotations, clip.translations @ quarter.T, name="turned")
    assert turned.name == "turned" and turned.contacts is None
    assert np.max(np.abs(turned.positions - clip.positions @ quarter.T)) < 1e-9
    # Every other frame at half the rate, written and read back.
    half = clip.with_frames(clip.rotations[::2], clip.translations[::2], fps=15)
    assert len(half) == (len(clip) + 1) // 2 and half.fps == 15
    half.save(tmp_path / "half.bvh")
    back = mg.load_clip(tmp_path / "half.bvh", keep_rest_frames=True)
    assert len(back) == len(half) and abs(back.fps - 15) < 1e-6
    assert np.max(np.abs(back.positions - half.positions)) < 1e-5
    joints = clip.rotations.shape[1]
    with pytest.raises(ValueError, match=rf"rotations must be frames x {joints} joints x 4, not \(10, {joints}, 3\)"):
        clip.with_frames(np.zeros((10, joints, 3)))
    with pytest.raises(ValueError, match="10 frames of rotations need their translations"):
        clip.with_frames(clip.rotations[:10])
    with pytest.raises(ValueError, match=r"rotations\[0, 0\] is not a rotation"):
        clip.with_frames(np.zeros_like(clip.rotations))
    bad = np.array(clip.translations)
    bad[3, 0, 1] = np.nan
    with pytest.raises(ValueError, match=r"translations\[3, 0\] is not finite"):
        clip.with_frames(clip.rotations, bad)


def test_numbers_are_not_true_or_false_and_misspelt_keywords_are_named(data, tmp_path):
    # pybind11 takes True and False for numbers (load_clip(fps=True) read a clip at 1 fps) and
    # answered a misspelt keyword with every signature; the keyword options already did neither.
    amc = str(data / "cmu/16/16_15.amc")
    clip = mg.load_clip(amc, fps=30)
    calls = {
        "load_clip fps": lambda: mg.load_clip(amc, fps=True),
        "load_clip scale": lambda: mg.load_clip(amc, scale=True),
        "load_clip input_fps": lambda: mg.load_clip(amc, input_fps=False),
        "save output_scale": lambda: clip.save(str(tmp_path / "b.bvh"), output_scale=True),
        "save root_motion_smoothing": lambda: clip.save(str(tmp_path / "b.bvh"), root_motion=True,
                                                        root_motion_smoothing=True),
        "with_frames fps": lambda: clip.with_frames(clip.rotations, fps=True),
        "load_clip fps numpy": lambda: mg.load_clip(amc, fps=np.True_),  # numpy's bool is no bool subclass
    }
    for what, call in calls.items():
        with pytest.raises(TypeError, match="a number is expected, not (True|False)"):
            call()
        assert not (tmp_path / "b.bvh").exists(), what
    # The same calls with numbers work.
    assert abs(len(mg.load_clip(amc, fps=60)) - 2 * len(clip)) <= 1
    assert clip.with_frames(clip.rotations, fps=15).fps == 15
    clip.save(str(tmp_path / "b.bvh"), output_scale=100)
    assert mg.load_clip(str(tmp_path / "b.bvh"), scale=0.01).frame_count == clip.frame_count
    for call, keyword in [(lambda: mg.load_clip(amc, fsp=30), "fsp"),
                          (lambda: clip.save(str(tmp_path / "c.bvh"), outputscale=1), "outputscale"),
                          (lambda: clip.with_frames(clip.rotations, fp=30), "fp"),
                          (lambda: mg.save_animations(str(tmp_path / "c.glb"), [clip], name=["a"]), "name"),
                          (lambda: mg.load_graph(str(tmp_path / "none.mgraph"), skeletons=0), "skeletons")]:
        with pytest.raises(TypeError) as raised:
            call()
        assert str(raised.value).endswith(f"() got an unexpected keyword argument '{keyword}'"), raised.value
    assert not (tmp_path / "c.bvh").exists() and not (tmp_path / "c.glb").exists()
    # save_animations' smoothing needs root motion, as save()'s does.
    with pytest.raises(ValueError, match="root_motion_smoothing needs root_motion=True"):
        mg.save_animations(str(tmp_path / "c.glb"), [clip], root_motion_smoothing=1)
