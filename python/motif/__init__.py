"""motif: synthesize patterns from examples, numpy in and out.

One function per engine; keyword arguments are the ``motif`` CLI's flags with ``-`` written ``_``
(``patch_size=7`` for ``--patch-size 7``) and have the CLI's defaults, so a command line and a call
with the same options and ``seed`` give the same bytes. Images are ``uint8`` arrays H×W, H×W×1,
H×W×3 or H×W×4 (results are H×W×4, straight alpha). Every call releases the GIL while the engine
runs; ``threads`` caps its worker threads (default: all cores; results do not depend on it).
``report=True`` also returns the run's figures as a dict (the CLI's ``--report``).

Bad options raise ``motif.OptionError`` naming the option, unusable inputs ``motif.InputError``
and runs past a memory, point or work limit ``motif.LimitError`` (all ``motif.MotifError``, a
``ValueError``; ``LimitError`` is a ``MemoryError`` too); files that cannot be read or written
raise ``OSError``.

>>> import numpy as np, motif
>>> exemplar = (np.random.default_rng(1).random((32, 32, 3)) * 255).astype(np.uint8)
>>> motif.texture(exemplar, (64, 48), seed=3).shape
(48, 64, 4)
"""

from __future__ import annotations

import json
import os
from typing import Any, Dict, Iterable, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _motif

__all__ = [
    "texture",
    "inpaint",
    "zoom",
    "video",
    "stylize",
    "presynth",
    "curve",
    "points",
    "strokes",
    "tiles",
    "read_image",
    "write_png",
    "read_points",
    "options",
    "jobs",
    "Textures",
    "MotifError",
    "OptionError",
    "InputError",
    "LimitError",
]

# A run the engines refuse raises one of these (all ValueError): a bad option, an unusable input,
# or a limit the run would pass (memory, points, work; LimitError is also a MemoryError).
MotifError = _motif.MotifError
OptionError = _motif.OptionError
InputError = _motif.InputError
LimitError = _motif.LimitError

#: Pre-synthesized textures, one per segment colour (``presynth``'s result, for ``stylize``).
Textures = _motif.Textures

ArrayLike = Any


# Job fields that each function takes as its own arguments, not as options.
_ARGUMENTS = {
    "texture": {"size", "seed"},
    "inpaint": {"seed"},
    "zoom": {"size", "factor", "levels", "seed"},
    "video": {"seed"},
    "stylize": {"weight", "seed"},
    "presynth": {"size", "seed"},
    "curve": {"width", "piece-length"},
    "points": {"neighbourhood", "domain", "seed"},
    "strokes": {"scale", "target", "seed"},
    "tiles": {"seed", "zoom"},
}


def _job(engine: str, fixed: Dict[str, Any], options: Dict[str, Any]) -> str:
    """The JSON job: fixed fields plus the options, named as the CLI's flags."""
    known = set(_motif.options(engine)) - _ARGUMENTS[engine]
    description = dict(fixed)
    for name, value in options.items():
        flag = name.replace("_", "-")
        if flag not in known:
            allowed = ", ".join(sorted(n.replace("-", "_") for n in known))
            raise TypeError(f"motif.{engine}() got an unknown option {name!r}; options: {allowed}")
        if value is None:
            continue
        value = _plain(value)
        if _has_non_finite(value):
            raise ValueError(f"invalid {flag} = {value!r}: NaN and infinite values are not allowed")
        description[flag] = value
    return json.dumps(description, allow_nan=False)


def _plain(value: Any) -> Any:
    """numpy scalars and arrays as JSON values."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    return value


def _seed(seed: Any) -> int:
    if isinstance(seed, (bool, np.bool_)) or not isinstance(seed, (int, np.integer)) or not 0 <= seed < 2**64:
        raise ValueError(f"seed must be an integer between 0 and 2**64 - 1, not {seed!r}")
    return int(seed)


def _has_non_finite(value: Any) -> bool:
    if isinstance(value, float):
        return not np.isfinite(value)
    if isinstance(value, list):
        return any(_has_non_finite(v) for v in value)
    if isinstance(value, dict):
        return any(_has_non_finite(v) for v in value.values())
    return False


def _image(array: ArrayLike, what: str) -> np.ndarray:
    array = np.asarray(array)
    if array.dtype != np.uint8:
        raise ValueError(f"{what}: images are uint8 arrays (0–255), not {array.dtype}; convert with .astype(np.uint8)")
    return array


def _finish(result: Any, report_text: str, report: bool) -> Any:
    return (result, json.loads(report_text)) if report else result


def texture(
    exemplar: ArrayLike,
    size: Tuple[int, int],
    *,
    seed: int = 1,
    threads: Optional[int] = None,
    report: bool = False,
    **options: Any,
) -> Any:
    """Grows a texture of ``size`` = (width, height) from ``exemplar`` (``motif texture``).

    Options: ``patch_size`` (5), ``coarse_patch_size`` (inferred without a quilt: 11, or 15 for an
    exemplar of 1024 pixels a side or more; 0: off),
    ``structure_weight`` (0: off; 3 keeps the gaps between elements), ``quilt_block`` (inferred:
    half the exemplar's side when the output is larger; 0: off), ``uniformity`` (3500), ``pyramid_levels``, ``search_vote_iters``,
    ``patchmatch_iters``, ``stop_threshold``, ``nnf`` ('patchmatch' or 'exact'), ``tileable``,
    ``max_pixels``, ``max_memory``; see ``motif texture --help``. Returns an H×W×4 uint8 array.
    """
    width, height = _size(size)
    job = _job("texture", {"size": [width, height], "seed": _seed(seed)}, options)
    image, report_text = _motif.texture(_image(exemplar, "exemplar"), job, threads)
    return _finish(image, report_text, report)


def inpaint(
    image: ArrayLike,
    hole: ArrayLike,
    *,
    seed: int = 1,
    threads: Optional[int] = None,
    report: bool = False,
    **options: Any,
) -> Any:
    """Fills the ``hole`` (an H×W bool array, True = fill) of ``image`` from the rest of it
    (``motif inpaint``): every pixel outside the hole is kept exactly. Options as for ``texture``.
    Returns an H×W×4 uint8 array.
    """
    mask = np.asarray(hole)
    if mask.dtype != np.bool_:
        raise ValueError(f"hole must be a bool array (True = fill), got {mask.dtype}")
    job = _job("inpaint", {"seed": _seed(seed)}, options)
    filled, report_text = _motif.inpaint(_image(image, "image"), np.ascontiguousarray(mask), job, threads)
    return _finish(filled, report_text, report)


def zoom(
    exemplar: ArrayLike,
    size: Tuple[int, int],
    *,
    factor: float = 2.0,
    levels: int = 4,
    seed: int = 1,
    threads: Optional[int] = None,
    report: bool = False,
    **options: Any,
) -> Any:
    """Zooms into a texture of ``exemplar`` without end (``motif zoom``): ``levels`` images of
    ``size`` = (width, height), each ``factor`` times closer than the one before and synthesized
    at full resolution, guided by the centre of the one before. Options as for ``texture``.
    Returns a list of H×W×4 uint8 arrays, outermost first (with ``report=True``, also the list of
    their reports).
    """
    width, height = _size(size)
    fixed = {"size": [width, height], "factor": float(factor), "levels": int(levels), "seed": _seed(seed)}
    job = _job("zoom", fixed, options)
    images, reports = _motif.zoom(_image(exemplar, "exemplar"), job, threads)
    if report:
        return list(images), [json.loads(text) for text in reports]
    return list(images)



def _video_inputs(frames: Sequence[ArrayLike], mask: Optional[ArrayLike]) -> Tuple[List[np.ndarray], Optional[np.ndarray]]:
    frames = [_image(frame, f"frame {index}") for index, frame in enumerate(frames)]
    if mask is None:
        return frames, None
    hole = np.asarray(mask)
    if hole.dtype != np.bool_:
        raise ValueError(f"mask must be a bool array (True = synthesize), got {hole.dtype}")
    return frames, np.ascontiguousarray(hole)


def video(
    frames: Sequence[ArrayLike],
    keyframes: Dict[int, ArrayLike],
    *,
    mask: Optional[ArrayLike] = None,
    seed: int = 1,
    threads: Optional[int] = None,
    report: bool = False,
    **options: Any,
) -> Any:
    """Stylizes a frame sequence from stylized keyframes (``motif video``): ``keyframes`` maps a
    frame index (from 0) to that frame as the artist stylized it. Every other frame is synthesized
    with the frames' colours and edges, the keyframe's positions and the previous output carried
    along the motion, forward and backward from keyframes and blended between two.

    Options: ``colour_weight`` (1), ``edge_weight`` (1), ``position_weight`` (4),
    ``temporal_weight`` (2; 0 stylizes frames independently), and the synthesis options of
    ``texture``. ``mask`` (H×W bool, True = synthesize) keeps the frames' own pixels elsewhere.
    Returns one H×W×4 uint8 array per frame. ``motif.batch.stylize_frames`` runs the keyframe
    intervals as Dask tasks and gives the same arrays.
    """
    frames, hole = _video_inputs(frames, mask)
    keys = [(int(index), _image(style, f"keyframe {index}")) for index, style in sorted(keyframes.items())]
    job = _job("video", {"seed": _seed(seed)}, options)
    images, report_text = _motif.video(frames, keys, hole, job, threads)
    return _finish(list(images), report_text, report)


def _video_interval(
    frames: Sequence[ArrayLike],
    interval: Tuple[int, int, bool, bool],
    first_style: Optional[ArrayLike],
    last_style: Optional[ArrayLike],
    *,
    mask: Optional[ArrayLike] = None,
    seed: int = 1,
    threads: Optional[int] = None,
    **options: Any,
) -> List[np.ndarray]:
    """One keyframe interval of ``video`` (for ``motif.batch``)."""
    frames, hole = _video_inputs(frames, mask)
    first = None if first_style is None else _image(first_style, "keyframe")
    last = None if last_style is None else _image(last_style, "keyframe")
    job = _job("video", {"seed": _seed(seed)}, options)
    images, _ = _motif.video_interval(frames, tuple(interval), first, last, hole, job, threads)
    return list(images)


def _size(size: Any) -> Tuple[int, int]:
    try:
        width, height = (int(v) for v in size)
    except (TypeError, ValueError):
        raise ValueError(f"size must be (width, height), not {size!r}") from None
    if width <= 0 or height <= 0:
        raise ValueError(f"size must be positive, not {width}×{height}")
    return width, height


def stylize(
    style: ArrayLike,
    guides: Sequence[Sequence[ArrayLike]],
    *,
    textures: Optional[Any] = None,
    seed: int = 1,
    threads: Optional[int] = None,
    report: bool = False,
    **options: Any,
) -> Any:
    """Stylizes: ``style`` is A', ``guides`` a list of (A, B) or (A, B, weight) (``motif stylize``).

    The output has the target guides' size. Options: ``style_weight``, ``uniformity``,
    ``patch_size``, ``pyramid_levels``, ``search_vote_iters``, ``patchmatch_iters``,
    ``stop_threshold``, ``nnf``, ``extra_pass_3x3``, ``segments``, ``segment_count``,
    ``segment_guide``, ``band``, ``max_pixels``, ``max_memory``. ``textures``: the result of
    :func:`presynth` for the style and its segment guide (``motif stylize --presynth``): the target
    is filled from them and only a band along segment edges is optimized. Returns an H×W×4 uint8
    array.
    """
    if textures is not None and not isinstance(textures, Textures):
        raise TypeError(f"textures must be the result of motif.presynth(), not {type(textures).__name__}")
    pairs = []
    weights = []
    for index, guide in enumerate(guides):
        if len(guide) not in (2, 3):
            raise ValueError(f"guide {index + 1}: give (source, target) or (source, target, weight)")
        pairs.append((_image(guide[0], f"source guide {index + 1}"), _image(guide[1], f"target guide {index + 1}")))
        if len(guide) == 3:
            weights.append(float(guide[2]))
    if weights and len(weights) != len(pairs):
        raise ValueError("give a weight for every guide pair or for none")
    fixed: Dict[str, Any] = {"seed": _seed(seed)}
    if weights:
        fixed["weight"] = weights
    job = _job("stylize", fixed, options)
    image, report_text = _motif.stylize(_image(style, "style"), pairs, job, textures, threads)
    return _finish(image, report_text, report)


def presynth(
    style: ArrayLike,
    guide: ArrayLike,
    size: Optional[Tuple[int, int]] = None,
    *,
    seed: int = 1,
    threads: Optional[int] = None,
    report: bool = False,
    **options: Any,
) -> Any:
    """One seamless texture per segment colour of ``guide`` from ``style`` (``motif presynth``).

    ``size`` = (width, height) of each texture (256 × 256 unless given). Options as
    :func:`stylize`'s shared ones, plus ``segment_count`` (k-means colours, for anti-aliased
    guides). Returns a :class:`Textures` (``len()``, ``colours()``, ``images()``) to pass to
    ``stylize(textures=...)``.
    """
    fixed: Dict[str, Any] = {"seed": _seed(seed)}
    if size is not None:
        fixed["size"] = list(_size(size))
    job = _job("presynth", fixed, options)
    textures, report_text = _motif.presynth(_image(style, "style"), _image(guide, "guide"), job, threads)
    return _finish(textures, report_text, report)


def curve(
    exemplar: ArrayLike,
    path: ArrayLike,
    width: Optional[float] = None,
    piece_length: Optional[float] = None,
    *,
    more_exemplars: Iterable[ArrayLike] = (),
    avoid: Optional[ArrayLike] = None,
    start_tile_image: Optional[ArrayLike] = None,
    end_tile_image: Optional[ArrayLike] = None,
    corner_tile_image: Optional[ArrayLike] = None,
    seed: int = 1,
    threads: Optional[int] = None,
    report: bool = False,
    **options: Any,
) -> Any:
    """Lays the pattern of ``exemplar`` along ``path``, an (N, 2) array of points (closed when the
    last repeats the first), in a ribbon ``width`` wide cut into pieces of ``piece_length``
    (``motif curve``). Either left out (``None``) is inferred from ``exemplar``, as the CLI does:
    the width from the pattern's height, the piece length from its period along x.

    Options: ``scale``, ``closed``, ``method``, ``solver``, ``alpha``, ``gamma``, ``stitch``,
    ``canvas`` ((W, H)), ``margin``, ``samples``, ``variety``, ``pieces_shape``, ``width_profile``,
    ``round_bends``, ``fidelity``, ``max_memory``, ... ``start_tile_image``, ``end_tile_image`` and
    ``corner_tile_image`` are tiles from images of their own (H×W×4 uint8, their whole pattern),
    in place of the ``start_tile``, ``end_tile`` and ``corner_tile`` columns. Returns (image,
    pieces): an H×W×4 uint8 array and a list of dicts, one per piece (the CLI's ``--pieces``
    entries).
    """
    del seed  # The curve engine is deterministic; accepted for a uniform signature.
    points = np.ascontiguousarray(np.asarray(path, dtype=np.float64))
    if points.ndim != 2 or points.shape[1] != 2:
        raise ValueError(f"path must be an (N, 2) array of points, not shape {points.shape}")
    fixed = {"width": width, "piece-length": piece_length}
    job = _job("curve", {k: float(v) for k, v in fixed.items() if v is not None}, options)
    more = [_image(m, f"exemplar {i + 2}") for i, m in enumerate(more_exemplars)]
    avoid_image = None if avoid is None else _image(avoid, "avoid")
    tiles = [
        None if image is None else _image(image, name)
        for image, name in (
            (start_tile_image, "start_tile_image"),
            (end_tile_image, "end_tile_image"),
            (corner_tile_image, "corner_tile_image"),
        )
    ]
    image, pieces, report_text = _motif.curve(
        _image(exemplar, "exemplar"), points, job, more, avoid_image, threads, tiles
    )
    return _finish((image, json.loads(pieces)), report_text, report)


PointData = Union[ArrayLike, Dict[str, ArrayLike]]


def _columns(data: PointData, what: str) -> List[Tuple[str, bool, np.ndarray]]:
    if isinstance(data, dict):
        columns = []
        for name, values in data.items():
            values = np.asarray(values)
            if values.ndim != 1:
                raise ValueError(f"{what}: column {name!r} must be one-dimensional, not shape {values.shape}")
            integer = np.issubdtype(values.dtype, np.integer) or values.dtype == np.bool_
            columns.append((str(name), bool(integer), np.ascontiguousarray(values, dtype=np.float64)))
        return columns
    array = np.asarray(data, dtype=np.float64)
    if array.ndim != 2 or array.shape[1] not in (2, 3):
        raise ValueError(f"{what}: give a dict of columns or an (N, 2) or (N, 3) array, not shape {array.shape}")
    return [(axis, False, np.ascontiguousarray(array[:, a])) for a, axis in enumerate("xyz"[: array.shape[1]])]


def _surface_directions(directions: Any) -> Any:
    """``surface_directions`` as the job's JSON: "curvature", one direction, or one per vertex."""
    if isinstance(directions, str):
        if directions != "curvature":
            raise ValueError(f'surface_directions must be "curvature", a (3,) direction or a (V, 3) array, got {directions!r}')
        return "curvature"
    array = np.asarray(directions, dtype=np.float64)
    if array.shape == (3,):
        return {"constant": array.tolist()}
    if array.ndim == 2 and array.shape[1] == 3:
        return {"per-vertex": array.tolist()}
    raise ValueError(f"surface_directions must be a (3,) direction or a (V, 3) array, got shape {array.shape}")


def points(
    exemplar: PointData,
    neighbourhood: Optional[float] = None,
    *,
    domain: Any = None,
    along: Optional[ArrayLike] = None,
    brush_width: Optional[float] = None,
    scale_along: Optional[Tuple[float, float]] = None,
    volume: Optional[Tuple[ArrayLike, ArrayLike]] = None,
    surface: Optional[Tuple[ArrayLike, ArrayLike]] = None,
    surface_directions: Any = "curvature",
    existing: Optional[PointData] = None,
    rotation_map: Optional[ArrayLike] = None,
    scale_map: Optional[ArrayLike] = None,
    seed: int = 1,
    threads: Optional[int] = None,
    report: bool = False,
    **options: Any,
) -> Any:
    """Synthesizes a point pattern like ``exemplar`` (``motif points``).

    ``exemplar`` is a dict of 1-D arrays (``x``, ``y``, optionally ``z``, ``element``, and any
    attributes; integer arrays stay discrete) or an (N, 2|3) array of positions. The domain is
    ``domain=(W, H)`` or ``(W, H, D)`` (a box from the origin), ``domain=polygon`` (an (M, 2)
    outline), ``along=polyline, brush_width=w`` (a brush stroke), ``volume=(vertices, triangles)``
    (the inside of a closed triangle mesh: (V, 3) floats and (T, 3) integers), or
    ``surface=(vertices, triangles)`` (a 2D exemplar laid on the mesh, 3D output on it, oriented
    by ``surface_directions``: ``"curvature"``, one (3,) direction, or a (V, 3) array of one vector
    per vertex). ``neighbourhood`` is δ (default: inferred from the exemplar, 4 times its mean
    nearest-neighbour spacing in 2D and 2 times in 3D; the report states it).
    Options: ``sigma``, ``init``, ``refine``, ``statistics_iterations`` (40; 0: off), ``patch_size``, ``exemplar_window``,
    ``attribute_weight``, ``max_points``, ``max_memory``, ... ``rotation_map`` and ``scale_map``
    (2D) are uint8 images over the domain's bounding box, as ``--rotation-map`` (360° × grey) and
    ``--scale-map`` (2^(2·grey − 1)). Returns a dict of 1-D arrays.
    """
    if along is not None:
        if brush_width is None:
            raise ValueError("along needs brush_width")
        stroke: Dict[str, Any] = {"points": _plain(np.asarray(along, dtype=np.float64)), "width": float(brush_width)}
        if scale_along is not None:
            stroke["scale-along"] = [float(v) for v in scale_along]
        spec: Dict[str, Any] = {"stroke": stroke}
    elif volume is not None or surface is not None:
        if volume is not None and surface is not None:
            raise ValueError("give volume= or surface=, not both")
        vertices, triangles = volume if volume is not None else surface  # type: ignore[misc]
        vertex_array = np.asarray(vertices, dtype=np.float64)
        triangle_array = np.asarray(triangles)
        if vertex_array.ndim != 2 or vertex_array.shape[1] != 3:
            raise ValueError(f"mesh vertices must be a (V, 3) array, got shape {vertex_array.shape}")
        if triangle_array.ndim != 2 or triangle_array.shape[1] != 3 or not np.issubdtype(triangle_array.dtype, np.integer):
            raise ValueError(f"mesh triangles must be a (T, 3) integer array, got {triangle_array.dtype} {triangle_array.shape}")
        if triangle_array.size and (triangle_array.min() < 0 or triangle_array.max() >= len(vertex_array)):
            raise ValueError(f"mesh triangles must index the {len(vertex_array)} vertices")
        mesh = {"vertices": _plain(vertex_array), "triangles": triangle_array.astype(np.int64).tolist()}
        if volume is not None:
            spec = {"volume": mesh}
        else:
            spec = {"surface": {"mesh": mesh, "directions": _surface_directions(surface_directions)}}
    elif domain is None:
        raise ValueError(
            "give domain=(W, H) (a box), domain=polygon, along=polyline with brush_width, volume= or surface="
        )
    else:
        shape = np.asarray(domain, dtype=np.float64)
        spec = {"box": shape.tolist()} if shape.ndim == 1 else {"region": shape.tolist()}
    fixed: Dict[str, Any] = {"domain": spec, "seed": _seed(seed)}
    if neighbourhood is not None:
        fixed["neighbourhood"] = float(neighbourhood)
    job = _job("points", fixed, options)
    existing_columns = None if existing is None else _columns(existing, "existing")
    maps = [None if m is None else _image(m, name) for m, name in ((rotation_map, "rotation_map"), (scale_map, "scale_map"))]
    columns, report_text = _motif.points(_columns(exemplar, "exemplar"), job, existing_columns, threads, *maps)
    result = {name: (values.astype(np.int64) if integer else values) for name, integer, values in columns}
    return _finish(result, report_text, report)


def strokes(
    reference_svg: str,
    scale: Optional[float] = None,
    *,
    rect: Optional[Tuple[float, float]] = None,
    along: Optional[ArrayLike] = None,
    region: Optional[ArrayLike] = None,
    size: Optional[Tuple[float, float]] = None,
    tolerance: Optional[float] = None,
    density_map: Optional[ArrayLike] = None,
    scale_map: Optional[ArrayLike] = None,
    seed: int = 1,
    threads: Optional[int] = None,
    report: bool = False,
    **options: Any,
) -> Any:
    """Grows the stroke pattern of ``reference_svg`` (SVG text) at scale ε = ``scale`` inside
    ``rect=(W, H)``, along a polyline ``along`` or inside a polygon ``region`` (``motif strokes``).

    ``scale`` left out (or None) is inferred from the reference, as ``motif strokes`` without
    ``--scale`` does; the report (``report=True``) gives the ε used as ``scale``, with
    ``scale_inferred`` and ``scale_inference`` (method, and the joining distances below and above).

    ``density_map`` and ``scale_map`` are uint8 images (H×W grey or H×W×C) stretched over a
    region target's bounding box, as ``--density-map`` and ``--scale-map``: darkness is the
    density relative to the reference's; the scale is 2^(2·grey − 1).

    ``size`` is the output document's (width, height) (default: the rectangle, or the target's
    extent). ``tolerance`` flattens the reference's curves, as ``--tolerance`` (default and range
    declared once, in motif-jobs: 0.1, 0.001–100). Options: ``fit``, ``rings``, ``variation``, ``position_variation``,
    ``allow_overlaps``, ``thresholds`` (a dict of shape, par, ov, sup, col, attr),
    ``lloyd_iterations``, ``max_memory``. Returns SVG text.
    """
    given = [name for name, value in (("rect", rect), ("along", along), ("region", region)) if value is not None]
    if len(given) != 1:
        raise ValueError("give exactly one target: rect=(W, H), along=polyline or region=polygon")
    if rect is not None:
        width, height = (float(v) for v in rect)
        target: Dict[str, Any] = {"rect": [width, height]}
        extent = (width, height)
    else:
        outline = np.asarray(along if along is not None else region, dtype=np.float64)
        if outline.ndim != 2 or outline.shape[1] != 2:
            raise ValueError(f"{given[0]} must be an (N, 2) array of points, not shape {outline.shape}")
        target = {given[0]: outline.tolist()}
        extent = (float(outline[:, 0].max()), float(outline[:, 1].max()))
    document = tuple(float(v) for v in (size if size is not None else extent))
    fixed: Dict[str, Any] = {"target": target, "seed": _seed(seed)}
    if scale is not None:
        fixed["scale"] = float(scale)
    job = _job("strokes", fixed, options)
    maps = [None if m is None else _image(m, name) for m, name in ((density_map, "density_map"), (scale_map, "scale_map"))]
    tolerance = None if tolerance is None else float(tolerance)
    svg, report_text = _motif.strokes(reference_svg, job, document, tolerance, threads, *maps)
    return _finish(svg, report_text, report)


def read_image(path: str) -> np.ndarray:
    """Reads a PNG, JPEG or WebP as an H×W×4 uint8 array."""
    return _motif.read_image(path)


def write_png(path: str, image: ArrayLike) -> None:
    """Writes an image array as an 8-bit RGBA PNG (atomically)."""
    _motif.write_png(path, _image(image, "image"))


def read_points(path: str) -> Dict[str, np.ndarray]:
    """Reads a PLY or CSV point file as a dict of 1-D arrays (integer columns as int64)."""
    return {name: (v.astype(np.int64) if integer else v) for name, integer, v in _motif.read_points(path)}


def jobs() -> List[Tuple[str, str]]:
    """Every job as (name, summary): each is a function of this module and a ``motif`` command."""
    return list(_motif.jobs())


def options(engine: str) -> List[str]:
    """The option names a job accepts (a name from :func:`jobs`), as keyword names."""
    if engine not in _ARGUMENTS:
        raise ValueError(f"no engine named {engine!r}; engines: {', '.join(sorted(_ARGUMENTS))}")
    return sorted(name.replace("-", "_") for name in set(_motif.options(engine)) - _ARGUMENTS[engine])


def tiles(
    map: Union[str, "os.PathLike[str]"],
    legend: Optional[Union[str, "os.PathLike[str]"]] = None,
    *,
    zoom: Optional[Tuple[int, int]] = None,
    seed: int = 1,
    threads: Optional[int] = None,
    **options: Any,
) -> Any:
    """A stylized slippy map of the OpenStreetMap extract ``map`` (``motif tiles``).

    ``legend`` is a folder of CLASS.png textures or a STYLE.json (default: the built-in legend of
    real GIMP textures); ``zoom`` = (low, high), the levels of ``pyramid()`` (default (12, 16)).
    The textures are pre-synthesized once, here; the result's ``render(z, x, y, layer="stylized")``
    gives any tile as an H×W×4 array ("plain" for the segment map), ``pyramid()`` lists the
    tiles of ``zoom`` over the map and ``report()`` the run's figures as JSON. Tiles have the
    bytes of ``motif tiles`` with the same options and seed. It pickles with its textures (a
    Dask worker reads the map and legend again but does not pre-synthesize).
    """
    fixed: Dict[str, Any] = {"seed": _seed(seed)}
    if zoom is not None:
        fixed["zoom"] = [int(zoom[0]), int(zoom[1])]
    job = _job("tiles", fixed, options)
    return _motif.tiles(os.fspath(map), job, None if legend is None else os.fspath(legend), threads)
