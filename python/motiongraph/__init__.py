"""Motion graphs (Kovar, Gleicher & Pighin 2002) from motion capture.

    import motiongraph as mg
    clip = mg.load_clip("data/cmu/16/16_15.amc")        # clip.positions: frames x joints x 3
    library = mg.load_library("data/cmu/16")             # the clips as build reads them, and a summary
    graph = mg.build(["data/cmu/16"])                    # options as the CLI's build, snake_case
    motion = graph.path(shape="figure8:4", segments=["walk:0-25", "run:25-51"])
    motion.save("figure8.bvh")

See docs/python.md.
"""
import functools as _functools
import io as _io
import operator as _operator
import os as _os
import re as _re

from ._motiongraph import Controller, EmptyGraphError, Error, Graph, Motion, load_clip, load_graph, save_animations
from ._motiongraph import _build, _load_library


def _keywords_named(function):
    # pybind11 answers a keyword it does not know with every signature of the function; this names
    # the keyword, as a Python function does, from the parameters its signature (the docstring's
    # first line) gives.
    signature = function.__doc__.split("\n", 1)[0]
    name = signature.split("(", 1)[0]
    known = frozenset(_re.findall(r"[(,]\s*(\w+):", signature.split(" -> ", 1)[0])) - {"self"}

    @_functools.wraps(function)
    def checked(*args, **kwargs):
        for keyword in kwargs:
            if keyword not in known:
                raise TypeError(f"{name}() got an unexpected keyword argument '{keyword}'")
        return function(*args, **kwargs)

    checked._keywords = known
    return checked


load_clip = _keywords_named(load_clip)
load_graph = _keywords_named(load_graph)
save_animations = _keywords_named(save_animations)
Motion.save = _keywords_named(Motion.save)
Motion.with_frames = _keywords_named(Motion.with_frames)
Controller.step = _keywords_named(Controller.step)

__all__ = ["Controller", "EmptyGraphError", "Error", "Graph", "Library", "Motion", "build", "load_clip",
           "load_graph", "load_library", "save_animations"]


def _paths(inputs):
    # As the file system's bytes: a name that is not UTF-8 (b"libl\xe9", or its os.fsdecode) too.
    if isinstance(inputs, (str, bytes, _os.PathLike)):
        inputs = [inputs]
    return [_os.fsencode(i) for i in inputs]


def build(inputs, progress=None, **options):
    """Builds the motion graph of `inputs` (folders, clip files or .toml manifests; one or a list).

    Keywords are the CLI's build options in snake_case (fps=30, threshold="4cm", cloud="joints",
    no_path_check=True, cache_dir=..., no_cache=True, ...), plus distance_matrix=True and clouds=True
    to keep those for Graph.distance_matrix() and Graph.clouds(). `progress`, when given, is called
    with each line the build logs, and every 2 s of reading, of the distance stage, of the threshold
    choice and of the path check with how far they got ("distance: 45 % (4500 of 10000) in 12.3 s,
    about 15 s left"); an exception it raises
    stops the build at its next step and is raised, as Ctrl-C's KeyboardInterrupt is. Raises
    motiongraph.Error with the CLI's message, or EmptyGraphError (with .report) when pruning leaves
    nothing.
    """
    return _build(_paths(inputs), options, progress)


class Library:
    """A motion library as build reads it: its clips (Motion, at the library's rate, with their feet's
    contacts) and its summary (the dict `motiongraph info --json` prints for the same inputs).

    len(library) is its clip count; library[i] or library["16_15"] a clip, library[i:j] a list of
    clips; iterating gives the clips; "16_15" in library asks for a clip by name.
    """

    def __init__(self, summary, clips):
        self.summary = summary
        self.clips = clips

    @property
    def fps(self):
        """The library's frame rate: every clip is resampled to it."""
        return self.summary["fps"]

    @property
    def frame_count(self):
        return self.summary["frames"]

    @property
    def tags(self):
        """{tag: {"clips", "frames", "seconds"}}: how much of the library each motion type holds."""
        return self.summary["tags"]

    @property
    def warnings(self):
        """What loading doubts or chose against a file's own voice, one line each (also given as
        UserWarning when the library is loaded)."""
        return self.summary["warnings"]

    def clip_tags(self, clip):
        """The tags of a clip (index, name or the clip itself) as [(tag, first_frame, frame_count), ...]
        in its own frames."""
        index = self._index(clip)
        return [(r["tag"], r["first_frame"], r["frames"]) for r in self.summary["clips"][index]["tag_ranges"]]

    def _index(self, clip):
        if isinstance(clip, str):
            for index, row in enumerate(self.summary["clips"]):
                if row["name"] == clip:
                    return index
            raise KeyError(clip)
        if isinstance(clip, Motion):
            for index, c in enumerate(self.clips):
                if c is clip:
                    return index
            raise KeyError(f"{clip!r} is not a clip of this library")
        # An index: an int or anything that is one (numpy's integers), not True or False.
        if isinstance(clip, bool) or type(clip).__name__ in ("bool_", "bool") or not hasattr(clip, "__index__"):
            raise TypeError(f"a clip is given by its index, its name or itself (a Motion of the library), "
                            f"not {type(clip).__name__}")
        clip = _operator.index(clip)
        count = len(self.clips)
        if not -count <= clip < count:
            raise IndexError(f"clip {clip} out of range: the library has {count} clips")
        return range(count)[clip]

    def __len__(self):
        return len(self.clips)

    def __getitem__(self, clip):
        if isinstance(clip, slice):
            return self.clips[clip]
        return self.clips[self._index(clip)]

    def __iter__(self):
        return iter(self.clips)

    def __contains__(self, clip):
        """A clip's name ("16_15" in library), or a Motion of the library."""
        if isinstance(clip, str):
            return any(row["name"] == clip for row in self.summary["clips"])
        return any(clip is c for c in self.clips)

    def __repr__(self):
        return (f"<motiongraph.Library: {len(self.clips)} clips, {self.frame_count} frames at {self.fps:g} fps, "
                f"tags {sorted(self.tags)}>")


def load_library(inputs, **options):
    """Reads a library as `build` does: inputs one path or a list (folders, clip files or .toml
    manifests), each clip resampled to the library's rate, tagged, on the joints all share.

    Keywords are build's options for reading: fps, asf, scale, up_axis, travel, input_fps, cmu_index,
    no_cmu_tags, no_name_tags, whole_clip_tags, keep_rest_frames, feet, no_loops, mirror ("auto", "on" or True,
    "off" or False).
    Loading's doubts (files read in the library's up axis,
    joints dropped, other converters' rigs, clips that look wrong) are given as UserWarning. Returns a Library; raises
    motiongraph.Error with the CLI's message.
    """
    return Library(*_load_library(_paths(inputs), options))


def _npy(data, what):
    if not data:
        raise Error(f"no {what}: only a graph built with {what}=True holds it (a .mgraph file keeps none)")
    import numpy
    return numpy.load(_io.BytesIO(data))


def _distance_matrix(self):
    """The N x N float32 distance matrix (NaN undefined; row: frame left, column: frame arrived at)."""
    return _npy(self._matrix_npy(), "distance_matrix")


def _clouds(self):
    """The N x P x 3 float32 point clouds, metres."""
    return _npy(self._clouds_npy(), "clouds")


def _tag_thresholds(self):
    """{motion type: {"threshold": D, "rms_cm": the same as RMS point distance over the window}}: the
    threshold each motion type's transitions pass (the build report's tag_thresholds; never below
    Graph.threshold, the lowest); empty for a graph built with one threshold for all."""
    rows = (self.report or {}).get("tag_thresholds") or []
    return {row["tag"]: {"threshold": row["threshold"], "rms_cm": row["rms_cm"]} for row in rows}


Graph.tag_thresholds = property(_tag_thresholds)
Graph.distance_matrix = _distance_matrix
Graph.clouds = _clouds
