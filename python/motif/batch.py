"""Large stylizations as many independent tasks on Dask: a big guide in overlapping tiles, a
frame sequence split into its keyframe intervals (``motif video``), or a map's tile pyramid
(``motif tiles render``).

motif schedules nothing itself: the tasks go to a ``dask.distributed`` ``Client`` (yours, or a
``LocalCluster`` started for the call and closed after it). The style and the source guides are
scattered to every worker once; each task stylizes one tile (or frame) with ``threads`` engine
threads.

Tiles: the target guides are cut into a grid of ``tile`` × ``tile`` cores; each task stylizes its
core grown by ``overlap`` pixels on every side (clipped at the image's border), and the results
are blended back with weights that fall linearly to zero across the overlap, so no tile's border
shows. The default overlap is ``4 × patch_size`` (20 pixels for the default 5×5 patches): wide
enough for the finest levels, where a seam would show, to agree across it.
"""

from __future__ import annotations

import os
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np

import motif

__all__ = ["stylize_tiles", "stylize_frames", "render_tiles", "tile_grid", "seam_error"]


def tile_grid(height: int, width: int, tile: int, overlap: int) -> List[Tuple[Tuple[int, int], Tuple[int, int, int, int], Tuple[int, int, int, int]]]:
    """The tiles of an image: ((row, column), core (y0, y1, x0, x1), extent with the overlap)."""
    if tile <= 0 or overlap < 0:
        raise ValueError(f"tile must be > 0 and overlap ≥ 0, not {tile} and {overlap}")
    tiles = []
    for row, y0 in enumerate(range(0, height, tile)):
        for column, x0 in enumerate(range(0, width, tile)):
            y1, x1 = min(y0 + tile, height), min(x0 + tile, width)
            extent = (max(0, y0 - overlap), min(height, y1 + overlap), max(0, x0 - overlap), min(width, x1 + overlap))
            tiles.append(((row, column), (y0, y1, x0, x1), extent))
    return tiles


def _ramp(length: int, low_pad: int, high_pad: int) -> np.ndarray:
    """Weights along one axis of a tile's extent: 1 in the core, falling linearly to ~0 across
    the overlap on each side that has one."""
    weights = np.ones(length, dtype=np.float64)
    if low_pad > 0:
        weights[:low_pad] = (np.arange(low_pad) + 0.5) / (low_pad + 0.5) * 0.5
    if high_pad > 0:
        weights[length - high_pad :] = ((np.arange(high_pad)[::-1] + 0.5) / (high_pad + 0.5)) * 0.5
    return weights


def _stylize_tile(style, sources, targets, weights, extent, options) -> np.ndarray:
    y0, y1, x0, x1 = extent
    guides = []
    for index, (source, target) in enumerate(zip(sources, targets)):
        guide = (source, np.ascontiguousarray(target[y0:y1, x0:x1]))
        guides.append(guide + (weights[index],) if weights else guide)
    return motif.stylize(style, guides, **options)


def _client(client: Any) -> Tuple[Any, Callable[[], None]]:
    """The given client, or a LocalCluster's (closed by the returned function)."""
    if client is not None:
        return client, lambda: None
    from dask.distributed import Client, LocalCluster

    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    local = Client(cluster)

    def close() -> None:
        local.close()
        cluster.close()

    return local, close


def stylize_tiles(
    style: np.ndarray,
    guides: Sequence[Sequence[Any]],
    *,
    tile: int = 512,
    overlap: Optional[int] = None,
    client: Any = None,
    threads: int = 1,
    seed: int = 1,
    out: Optional[str] = None,
    task: Callable[..., np.ndarray] = _stylize_tile,
    **options: Any,
) -> np.ndarray:
    """Stylizes a large target in overlapping tiles on Dask; returns the H×W×4 result.

    ``guides`` are (A, B) or (A, B, weight) as for :func:`motif.stylize`; every B is cut into
    tiles. Each tile gets the seed ``seed + tile index`` (tiles are independent runs). With
    ``out``, the result is written as a PNG once every tile has succeeded (a failing tile raises
    ``RuntimeError`` naming it, and nothing is written). ``task`` replaces the function run per
    tile (for tests). Other options are :func:`motif.stylize`'s.
    """
    style = np.asarray(style)
    sources = [np.asarray(g[0]) for g in guides]
    targets = [np.asarray(g[1]) for g in guides]
    weights = [float(g[2]) for g in guides if len(g) == 3]
    if not targets:
        raise ValueError("stylize_tiles needs at least one guide pair")
    height, width = targets[0].shape[:2]
    if overlap is None:
        overlap = 4 * int(options.get("patch_size", 5))
    grid = tile_grid(height, width, int(tile), int(overlap))
    dask_client, close = _client(client)
    try:
        # Unique keys (hash=False): scattered by content, an identical style from an earlier call
        # shares its key, and that call releasing it could cancel these tiles ("lost dependencies").
        shared_style = dask_client.scatter(style, broadcast=True, hash=False)
        shared_sources = dask_client.scatter(sources, broadcast=True, hash=False)
        futures = []
        for index, (_, _, extent) in enumerate(grid):
            tile_options = dict(options, seed=int(seed) + index, threads=int(threads))
            futures.append(
                dask_client.submit(task, shared_style, shared_sources, targets, weights, extent, tile_options, pure=False)
            )
        results = []
        for (position, core, extent), future in zip(grid, futures):
            try:
                results.append(future.result())
            except Exception as error:  # noqa: BLE001 - re-raised with the tile named
                row, column = position
                y0, y1, x0, x1 = core
                raise RuntimeError(
                    f"tile (row {row}, column {column}) covering x {x0}–{x1}, y {y0}–{y1} failed: {error}"
                ) from error
    finally:
        close()
    total = np.zeros((height, width, 4), dtype=np.float64)
    weight_sum = np.zeros((height, width, 1), dtype=np.float64)
    for (_, core, extent), image in zip(grid, results):
        ey0, ey1, ex0, ex1 = extent
        cy0, cy1, cx0, cx1 = core
        along_y = _ramp(ey1 - ey0, cy0 - ey0, ey1 - cy1)
        along_x = _ramp(ex1 - ex0, cx0 - ex0, ex1 - cx1)
        weight = np.outer(along_y, along_x)[:, :, None]
        total[ey0:ey1, ex0:ex1] += weight * image
        weight_sum[ey0:ey1, ex0:ex1] += weight
    result = np.clip(np.rint(total / weight_sum), 0, 255).astype(np.uint8)
    if out is not None:
        motif.write_png(out, result)
    return result


def stylize_frames(
    frames: Sequence[np.ndarray],
    keyframes: Dict[int, np.ndarray],
    *,
    client: Any = None,
    threads: int = 1,
    seed: int = 1,
    mask: Optional[np.ndarray] = None,
    **options: Any,
) -> List[np.ndarray]:
    """Stylizes a frame sequence from stylized keyframes on Dask, as ``motif.video`` does.

    ``keyframes`` maps a frame index (from 0) to that frame as the artist stylized it. The
    sequence splits into keyframe intervals (before the first keyframe, between two, after the
    last), which are independent: each is one task, and the frames are the bytes
    ``motif.video(frames, keyframes, seed=seed, ...)`` gives. Returns one H×W×4 array per frame.
    """
    if not keyframes:
        raise ValueError("stylize_frames needs at least one keyframe")
    for index in keyframes:
        if not 0 <= index < len(frames):
            raise ValueError(f"keyframe {index} is not a frame index (0–{len(frames) - 1})")
    intervals = motif._motif.video_intervals(len(frames), sorted(keyframes))
    dask_client, close = _client(client)
    try:
        futures = []
        for first, last, starts, ends in intervals:
            futures.append(
                dask_client.submit(
                    motif._video_interval,
                    [frames[i] for i in range(first, last + 1)],
                    (first, last, starts, ends),
                    keyframes[first] if starts else None,
                    keyframes[last] if ends else None,
                    mask=mask,
                    seed=seed,
                    threads=int(threads),
                    pure=False,
                    **options,
                )
            )
        results: List[Optional[np.ndarray]] = [None] * len(frames)
        for (first, last, _, _), future in zip(intervals, futures):
            try:
                part = future.result()
            except Exception as error:  # noqa: BLE001 - re-raised with the interval named
                raise RuntimeError(f"frames {first}–{last} failed: {error}") from error
            for offset, image in enumerate(part):
                if results[first + offset] is None:
                    results[first + offset] = image
    finally:
        close()
    return [image for image in results if image is not None]


def seam_error(image: np.ndarray, tile: int) -> float:
    """How much a tiled result jumps at tile borders: the mean colour step between neighbouring
    pixels across the borders, divided by the mean step everywhere else (about 1 without a
    visible seam)."""
    pixels = np.asarray(image, dtype=np.float64)[:, :, :3]
    step_x = np.abs(np.diff(pixels, axis=1)).mean(axis=2)
    step_y = np.abs(np.diff(pixels, axis=0)).mean(axis=2)
    border_x = np.zeros(step_x.shape[1], dtype=bool)
    border_x[tile - 1 :: tile] = True
    border_y = np.zeros(step_y.shape[0], dtype=bool)
    border_y[tile - 1 :: tile] = True
    at_borders = np.concatenate([step_x[:, border_x].ravel(), step_y[border_y, :].ravel()])
    elsewhere = np.concatenate([step_x[:, ~border_x].ravel(), step_y[~border_y, :].ravel()])
    if at_borders.size == 0 or elsewhere.mean() == 0:
        return 1.0
    return float(at_borders.mean() / elsewhere.mean())


def _render_tile(tiles: Any, tile: Tuple[int, int, int], layer: str, threads: int) -> Tuple[Tuple[int, int, int], bytes]:
    z, x, y = tile
    return tile, tiles.render_png(z, x, y, layer=layer, threads=threads)


def render_tiles(
    map: Any,
    zooms: Tuple[int, int] = (12, 16),
    out: Optional[str] = None,
    *,
    legend: Any = None,
    layer: str = "stylized",
    client: Any = None,
    threads: int = 1,
    seed: int = 1,
    **options: Any,
) -> Dict[Tuple[int, int, int], bytes]:
    """Renders the tile pyramid of ``motif tiles render`` on Dask: one task per tile.

    The tile set (:func:`motif.tiles` of ``map``, ``legend``, ``zooms``, ``seed`` and
    ``options``) is made here and scattered to every worker once, with its pre-synthesized
    textures (numpy arrays in its pickle): the workers read the map and legend again (their paths
    must be readable there) but do not pre-synthesize. Returns {(z, x, y): PNG bytes}; with
    ``out``, also writes them as one PMTiles archive, byte for byte the archive ``motif tiles
    render`` writes with the same options and seed.
    """
    legend_path = None if legend is None else os.path.abspath(os.fspath(legend))
    tiles = motif.tiles(os.path.abspath(os.fspath(map)), legend_path, zoom=zooms, seed=seed, **options)
    pyramid = tiles.pyramid()
    dask_client, close = _client(client)
    try:
        [remote] = dask_client.scatter([tiles], broadcast=True, hash=False)
        futures = [dask_client.submit(_render_tile, remote, tile, layer, threads, pure=False) for tile in pyramid]
        rendered = dask_client.gather(futures)
    finally:
        close()
    if out is not None:
        tiles.write_archive(os.fspath(out), rendered, layer)
    return dict(rendered)
