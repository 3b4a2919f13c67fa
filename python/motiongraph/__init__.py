"""Motion graphs (Kovar, Gleicher & Pighin 2002) from motion capture.

    import motiongraph as mg
    clip = mg.load_clip("data/cmu/16/16_15.amc")        # clip.positions: frames x joints x 3
    graph = mg.build(["data/cmu/16"])                    # options as the CLI's build, snake_case
    motion = graph.path(shape="figure8:4", segments=["walk:0-25", "run:25-51"])
    motion.save("figure8.bvh")

See docs/python.md.
"""
import io as _io
import os as _os

from ._motiongraph import Controller, EmptyGraphError, Error, Graph, Motion, load_clip, load_graph
from ._motiongraph import _build

__all__ = ["Controller", "EmptyGraphError", "Error", "Graph", "Motion", "build", "load_clip", "load_graph"]


def build(inputs, progress=None, **options):
    """Builds the motion graph of `inputs` (folders, clip files or .toml manifests; one or a list).

    Keywords are the CLI's build options in snake_case (fps=30, threshold="4cm", cloud="joints",
    no_path_check=True, cache_dir=..., no_cache=True, ...), plus distance_matrix=True and clouds=True
    to keep those for Graph.distance_matrix() and Graph.clouds(). `progress`, when given, is called
    with each line the build logs. Raises motiongraph.Error with the CLI's message, or
    EmptyGraphError (with .report) when pruning leaves nothing.
    """
    if isinstance(inputs, (str, _os.PathLike)):
        inputs = [inputs]
    return _build([_os.fspath(i) for i in inputs], options, progress)


def _npy(data, what):
    if not data:
        raise Error(f"no {what}: build the graph with {what}=True")
    import numpy
    return numpy.load(_io.BytesIO(data))


def _distance_matrix(self):
    """The N x N float32 distance matrix (NaN undefined; row: frame left, column: frame arrived at)."""
    return _npy(self._matrix_npy(), "distance_matrix")


def _clouds(self):
    """The N x P x 3 float32 point clouds, metres."""
    return _npy(self._clouds_npy(), "clouds")


Graph.distance_matrix = _distance_matrix
Graph.clouds = _clouds
