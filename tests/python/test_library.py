"""load_library() and Library: a library as build reads it, its summary the CLI's info --json."""
import json
import re
import warnings
from pathlib import Path

import numpy as np
import pytest

import motiongraph as mg
from conftest import cli_error


def cli_info(cli, *args):
    return json.loads(cli("info", "--json", *args).stdout)


def edited_bvh(text, offsets=1.0, root=lambda frame: frame):
    """A BVH file's text with its OFFSETs scaled and each frame's values edited by `root` (a list of
    floats in, a list out)."""
    head, motion = text.split("MOTION\n")
    head = re.sub(r"OFFSET (\S+) (\S+) (\S+)",
                  lambda m: "OFFSET " + " ".join(repr(float(v) * offsets) for v in m.groups()), head)
    lines = motion.splitlines()
    frames = [" ".join(repr(v) for v in root([float(v) for v in line.split()])) for line in lines[2:]]
    return head + "MOTION\n" + "\n".join(lines[:2] + frames) + "\n"


@pytest.mark.parametrize("fps", [None, 120.0])
def test_summary_is_the_cli_info_and_clips_are_load_clip(cli, data, fps):
    folder = data / "cmu/16"
    args = ["--fps", fps] if fps else []
    options = {"fps": fps} if fps else {}
    library = mg.load_library(folder, **options)
    assert library.summary == cli_info(cli, folder, *args)
    assert library.fps == (fps or 30.0)
    # At 120 fps, the files' 4920 frames less the two 16_15 opens on (cut off by a capture glitch).
    assert library.frame_count == sum(len(clip) for clip in library) == (4918 if fps else 1235)
    # Each clip is the file read and resampled as load_clip reads it, with the same contacts.
    assert [clip.name for clip in library] == [row["name"] for row in library.summary["clips"]]
    for clip, row in zip(library, library.summary["clips"]):
        alone = mg.load_clip(row["source"], fps=library.fps)
        assert clip.fps == library.fps and len(clip) == row["frames"]
        np.testing.assert_array_equal(clip.positions, alone.positions)
        np.testing.assert_array_equal(clip.rotations, alone.rotations)
        assert clip.foot_joints == alone.foot_joints == ["lfoot", "ltoes", "rfoot", "rtoes"]
        np.testing.assert_array_equal(clip.contacts, alone.contacts)


def test_tags_per_clip_add_up_to_the_totals(data):
    library = mg.load_library(data / "cmu/16")
    frames, clips = {}, {}
    for index, clip in enumerate(library):
        runs = library.clip_tags(index)
        assert runs == library.clip_tags(clip.name) == library.clip_tags(clip)  # by index, name or itself
        for tag, first, count in runs:
            assert 0 <= first and first + count <= len(clip)
            frames[tag] = frames.get(tag, 0) + count
        for tag in {tag for tag, _, _ in runs}:
            clips[tag] = clips.get(tag, 0) + 1
    assert {tag: (total["clips"], total["frames"]) for tag, total in library.tags.items()} == \
        {tag: (clips[tag], frames[tag]) for tag in frames}
    assert library.clip_tags("16_15") == [("walk", 0, len(library["16_15"]))]
    # A clip of another library, or given as what is no clip at all, is said to be so.
    with pytest.raises(KeyError, match="not a clip of this library"):
        library.clip_tags(mg.load_clip(data / "cmu/16/16_15.amc"))
    for bad in (None, True, 1.0, np.True_):
        with pytest.raises(TypeError, match="a clip is given by its index, its name or itself"):
            library[bad]
    assert library[np.int64(1)] is library[1] and library.clip_tags(np.int32(1)) == library.clip_tags(1)
    # "walk, stop": its walk stays where the root travels, its stop where it stands and the second
    # before, unless asked to keep them whole.
    stops = dict((tag, (first, count)) for tag, first, count in library.clip_tags("16_33"))
    assert stops["stop"] == (stops["walk"][1] - 30, len(library["16_33"]) - stops["walk"][1] + 30)
    assert stops["walk"][0] == 0
    assert len(library["16_33"]) // 2 < stops["walk"][1] < len(library["16_33"])
    standing = library.summary["reading"]["standing_tags"]
    assert {(t["clip"], t["tag"]) for t in standing} == {("16_33", "walk"), ("16_57", "run")}
    whole = mg.load_library(data / "cmu/16", whole_clip_tags=True)
    assert ("walk", 0, len(whole["16_33"])) in whole.clip_tags("16_33")
    assert ("stop", 0, len(whole["16_33"])) in whole.clip_tags("16_33")
    assert whole.summary["reading"]["standing_tags"] == []
    assert library[-1] is library.clips[-1] and len(library) == 15
    assert library[1:3] == library.clips[1:3] and len(library[1:3]) == 2
    with pytest.raises(KeyError):
        library["16_99"]
    assert "16_15" in library and "16_99" not in library and library[3] in library
    assert 3 not in library and mg.load_clip(data / "cmu/16/16_15.amc") not in library
    with pytest.raises(IndexError, match="^clip 15 out of range: the library has 15 clips$"):
        library[15]
    with pytest.raises(IndexError, match="^clip -16 out of range"):
        library[-16]


def test_units_chosen_and_doubts_warned(cli, data, tmp_path):
    """A folder of BVH in centimetres, one of them floating half a metre up: read in cm, the
    floating clip warned about as the CLI warns, and the same summary."""
    cli("convert", data / "cmu/16/16_15.amc", "-o", tmp_path / "walk_m.bvh")
    text = (tmp_path / "walk_m.bvh").read_text()
    folder = tmp_path / "lib"
    folder.mkdir()
    (folder / "walk.bvh").write_text(edited_bvh(text, 100.0, lambda v: [x * 100 for x in v[:3]] + v[3:]))
    (folder / "float.bvh").write_text(
        edited_bvh(text, 100.0, lambda v: [v[0] * 100, v[1] * 100 + 50, v[2] * 100] + v[3:]))
    with pytest.warns(UserWarning, match=r"^float: its lowest joint stays 0\.5.* above the floor") as caught:
        library = mg.load_library(folder)
    assert [str(w.message) for w in caught] == library.warnings
    assert library.summary == cli_info(cli, folder)
    units = library.summary["reading"]["units"]
    assert [(Path(u["file"]).name, u["unit"], u["metres_per_unit"], u["plausible"]) for u in units] == \
        [("float.bvh", "cm", 0.01, True), ("walk.bvh", "cm", 0.01, True)]
    # In metres, as the clip read from the metre file.
    np.testing.assert_allclose(library["walk"].positions, mg.load_clip(str(tmp_path / "walk_m.bvh"), fps=30).positions,
                               atol=1e-9)
    # Warnings as errors stop the load with the warning.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(UserWarning, match="^float: "):
            mg.load_library(folder)
    # Given a scale, no unit is chosen.
    assert mg.load_library(folder / "walk.bvh", scale=0.01).summary["reading"]["units"] == []


def test_clips_named_for_their_motion_are_tagged_by_their_names(cli, data, tmp_path):
    """A studio's files, not named like CMU's: tagged by the words of their names, as info says;
    no_name_tags (--no-name-tags) leaves them untagged."""
    folder = tmp_path / "studio"
    folder.mkdir()
    cli("convert", data / "cmu/16/16_15.amc", "-o", folder / "Walk_Forward.bvh")
    cli("convert", data / "cmu/16/16_16.amc", "-o", folder / "take_07.bvh")
    library = mg.load_library(folder)
    assert library.summary == cli_info(cli, folder)
    assert library.summary["reading"]["name_tags"] == [
        {"clip": "Walk_Forward", "tags": ["walk"], "source": "name", "words": "Walk_Forward"}]
    walk = library.clip_tags("Walk_Forward")
    assert [tag for tag, _, _ in walk] == ["walk"] and walk[0][2] > len(library["Walk_Forward"]) // 2
    assert library.clip_tags("take_07") == []
    plain = mg.load_library(folder, no_name_tags=True)
    assert plain.summary == cli_info(cli, folder, "--no-name-tags")
    assert plain.summary["reading"]["name_tags"] == [] and plain.tags == {}


def test_feet_named_and_options_refused(cli, data, tmp_path):
    bvh = data / "bvh/16_01.bvh"
    renamed = tmp_path / "pes.bvh"
    renamed.write_text(bvh.read_text().replace("lfoot", "lpes").replace("rfoot", "rpes"))
    unknown = mg.load_library(renamed)
    assert unknown.summary["feet"]["source"] is None and unknown[0].contacts is None
    named = mg.load_library(renamed, feet="lpes,,rpes,")
    assert named.summary["feet"]["source"] == "--feet"
    assert named[0].foot_joints == ["lpes", "ltoes", "rpes", "rtoes"]
    np.testing.assert_array_equal(named[0].contacts, mg.load_library(bvh)[0].contacts)
    assert mg.load_library(bvh, no_loops=True).summary["reading"]["loops"] == []
    # Only the options that say how clips are read; the rest of build's are refused.
    with pytest.raises(TypeError, match="load_library\\(\\) got an unexpected keyword argument 'threshold'"):
        mg.load_library(bvh, threshold="4cm")
    with pytest.raises(mg.Error, match="--travel must be auto, root or feet, not walk"):
        mg.load_library(bvh, travel="walk")
    # build --fps's range (0.5 fps was taken, a window of frames over 20 s).
    for fps in (0, 0.5, 1001):
        with pytest.raises(mg.Error, match=rf"fps must be 1 to 1000, not {fps}\b"):
            mg.load_library(bvh, fps=fps)


def test_rest_frames_kept_as_the_cli_and_a_manifest_say(cli, data, tmp_path):
    """07_01.bvh opens on a converter's T-pose frame: dropped by default, kept by the keyword, by
    the CLI's --keep-rest-frames and by a manifest's keep_rest_frames, at the top or on the clip;
    None is the keyword's default. The frames a capture glitch cuts off an AMC clip likewise."""
    bvh = data / "bvh/07_01.bvh"
    folder = tmp_path / "lib"
    folder.mkdir()
    (folder / bvh.name).write_bytes(bvh.read_bytes())
    at_120 = {"fps": 120}
    dropped = mg.load_library(folder, **at_120)
    kept = mg.load_library(folder, keep_rest_frames=True, **at_120)
    assert kept.frame_count == dropped.frame_count + 1
    assert dropped.summary["reading"]["rest_frames"] == [{"file": str(folder / bvh.name), "frames": 1}]
    assert kept.summary["reading"]["rest_frames"] == []
    assert kept.summary == cli_info(cli, folder, "--fps", 120, "--keep-rest-frames")
    assert mg.load_library(folder, keep_rest_frames=None, up_axis=None, scale=None, **at_120).summary == \
        dropped.summary
    # The clip as kept is the clip read by load_clip with its rest frame.
    np.testing.assert_allclose(kept[0].positions, mg.load_clip(bvh, keep_rest_frames=True).positions, atol=1e-9)
    path = bvh.as_posix()
    for manifest in (f'fps = 120\nkeep_rest_frames = true\n[[clip]]\nfile = "{path}"\n',
                     f'fps = 120\n[[clip]]\nfile = "{path}"\nkeep_rest_frames = true\n'):
        (tmp_path / "keep.toml").write_text(manifest)
        assert mg.load_library(tmp_path / "keep.toml").frame_count == kept.frame_count
    # The clip's own word wins over the manifest's.
    (tmp_path / "keep.toml").write_text(
        f'fps = 120\nkeep_rest_frames = true\n[[clip]]\nfile = "{path}"\nkeep_rest_frames = false\n')
    assert mg.load_library(tmp_path / "keep.toml").frame_count == dropped.frame_count
    amc = (data / "cmu/16/16_15.amc").as_posix()
    # 16_15 opens on two frames a capture glitch cuts off: the same word keeps them.
    (tmp_path / "amc.toml").write_text(f'fps = 120\n[[clip]]\nfile = "{amc}"\nkeep_rest_frames = true\n')
    (tmp_path / "amc0.toml").write_text(f'fps = 120\n[[clip]]\nfile = "{amc}"\n')
    glitched = mg.load_library(tmp_path / "amc0.toml")
    assert glitched.summary["reading"]["glitched_ends"] == [{"file": amc, "leading": 2, "trailing": 0}]
    assert mg.load_library(tmp_path / "amc.toml").frame_count == glitched.frame_count + 2
    # build reads the library as load_library does.
    cli("build", bvh, "--fps", 120, "--keep-rest-frames", "-o", tmp_path / "g.mgraph", "--report", tmp_path / "g.json",
        "-q")
    assert json.loads((tmp_path / "g.json").read_text())["frames"] == kept.frame_count


def test_bad_library_raises_the_cli_message(cli, data, tmp_path):
    missing = tmp_path / "nothing-here"
    missing.mkdir()
    with pytest.raises(mg.Error, match="holds no .amc, .bvh, .glb, .gltf or .fbx files") as raised:
        mg.load_library(missing)
    assert str(raised.value) == cli_error(cli("info", missing, check=False))
    broken = tmp_path / "broken.toml"
    amc = (data / "cmu/16/16_15.amc").as_posix()
    broken.write_text(f'[[clip]]\nfile = "{amc}"\nfirst_frame = 10\nlast_frame = 5\n')
    with pytest.raises(mg.Error, match="broken.toml:4: last_frame 5 comes before first_frame 10") as raised:
        mg.load_library(broken)
    assert str(raised.value) == cli_error(cli("info", broken, check=False))


def test_a_library_turning_one_way_is_mirrored_as_info_reads_it(cli, data, tmp_path):
    # 16_15 walks straight and 16_17 turns 90 degrees left: each is also read mirrored, after
    # them, as info (and build) reads the library; mirror=False or "off" reads them as they are,
    # True or "on" mirrors any library.
    folder = tmp_path / "left"
    folder.mkdir()
    for name in ("16.asf", "16_15.amc", "16_17.amc"):
        (folder / name).write_bytes((data / "cmu/16" / name).read_bytes())
    library = mg.load_library(folder)
    assert [c.name for c in library] == ["16_15", "16_17", "16_15_mirrored", "16_17_mirrored"]
    assert library.summary == cli_info(cli, folder)
    turning = library.summary["reading"]["turning"]
    assert turning["lopsided"] and turning["left_deg"] > 60 and turning["right_deg"] < turning["left_deg"] / 3
    assert library.summary["reading"]["mirrored"] == ["16_15_mirrored", "16_17_mirrored"]
    assert library.clip_tags("16_17_mirrored") == library.clip_tags("16_17")
    # The mirror image's root goes the clip's way mirrored (across the hips' plane, upright): as
    # high, as far from where it started, turning as far the other way (to the few millimetres
    # CMU's root stands beside the hips' middle).
    a, b = np.asarray(library["16_17"].positions)[:, 0], np.asarray(library["16_17_mirrored"].positions)[:, 0]
    np.testing.assert_allclose(b[:, 1], a[:, 1], atol=0.01)
    np.testing.assert_allclose(np.linalg.norm(b - b[0], axis=1), np.linalg.norm(a - a[0], axis=1), atol=0.01)

    def turn(root):  # radians, left positive: the travel's heading over the first second against the last
        u, v = root[30] - root[0], root[-1] - root[-31]
        return np.arctan2(u[2] * v[0] - u[0] * v[2], u[0] * v[0] + u[2] * v[2])
    assert turn(a) > 1.0 and abs(turn(b) + turn(a)) < 1e-3
    for off in (False, "off"):
        assert [c.name for c in mg.load_library(folder, mirror=off)] == ["16_15", "16_17"]
    assert mg.load_library(folder, mirror="off").summary == cli_info(cli, folder, "--mirror", "off")
    straight = tmp_path / "straight"
    straight.mkdir()
    for name in ("16.asf", "16_15.amc"):
        (straight / name).write_bytes((data / "cmu/16" / name).read_bytes())
    assert [c.name for c in mg.load_library(straight)] == ["16_15"]
    for on in (True, "on", np.bool_(True)):
        assert [c.name for c in mg.load_library(straight, mirror=on)] == ["16_15", "16_15_mirrored"]
    with pytest.raises(mg.Error, match="--mirror must be auto, on or off, not sometimes"):
        mg.load_library(folder, mirror="sometimes")
