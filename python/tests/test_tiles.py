"""`motif.tiles`: the stylized map of the real Helsinki extract, tile for tile the bytes the
`motif tiles serve` command answers with the same options and seed."""

import subprocess
import urllib.request

import numpy as np
import pytest

import motif
import motif.batch
from conftest import BINARY, ROOT

MAP = ROOT / "data" / "real" / "maps" / "Helsinki.osm.pbf"


def test_tiles_equal_the_servers(tmp_path):
    tiles = motif.tiles(MAP, zoom=(16, 16), seed=5, band=3)
    pyramid = tiles.pyramid()
    assert len(pyramid) == 24 and all(z == 16 for z, _, _ in pyramid)
    z, x, y = pyramid[9]
    stylized = tiles.render(z, x, y)
    plain = tiles.render(z, x, y, layer="plain")
    assert stylized.shape == plain.shape == (256, 256, 4)
    assert not np.array_equal(stylized, plain)
    server = subprocess.Popen(
        [str(BINARY), "--seed", "5", "--quiet", "tiles", "serve", "--map", str(MAP), "--band", "3", "--port", "0"]
        + ["--cache-dir", str(tmp_path / "cache"), "--max-requests", "1"],
        stdout=subprocess.PIPE,
        text=True,
    )
    try:
        address = server.stdout.readline().strip()
        with urllib.request.urlopen(f"{address}{z}/{x}/{y}.png", timeout=120) as response:
            (tmp_path / "tile.png").write_bytes(response.read())
    finally:
        assert server.wait(timeout=120) == 0
    assert np.array_equal(motif.read_image(str(tmp_path / "tile.png")), stylized)
    report = __import__("json").loads(tiles.report())
    assert report["margin"] == 3 + 5 and report["features"]["water"] > 0


def test_a_pickled_tile_set_carries_its_textures():
    """Pickling ships the pre-synthesized textures (numpy arrays): the copy does not run the
    presynthesis again and renders the same bytes; damaged textures are refused by name."""
    import json
    import pickle

    tiles = motif.tiles(MAP, zoom=(16, 16), seed=3, texture_size=32)
    copy = pickle.loads(pickle.dumps(tiles))
    assert json.loads(tiles.report())["presynthesized"] is True
    assert json.loads(copy.report())["presynthesized"] is False
    assert json.loads(copy.report())["presynth_ms"] == 0
    assert copy.render_png(16, 37308, 18968) == tiles.render_png(16, 37308, 18968)
    function, (map_path, job, legend, textures) = tiles.__reduce__()
    assert len(textures) == 8 and textures[0][1] == (32, 32, 3)
    with pytest.raises(motif.OptionError, match="textures"):
        function(map_path, job, legend, textures[1:])
    colour, shape, pixels, field = textures[0]
    with pytest.raises(motif.InputError, match="texture 1"):
        function(map_path, job, legend, [(colour, shape, pixels[:-1], field)] + textures[1:])


def test_bad_tile_options_are_refused_by_name():
    with pytest.raises(motif.OptionError, match="band"):
        motif.tiles(MAP, band=500)
    with pytest.raises(TypeError, match="bandwidth"):
        motif.tiles(MAP, bandwidth=3)
    tiles = motif.tiles(MAP, zoom=(16, 16), texture_size=32)
    with pytest.raises(motif.OptionError, match="layer"):
        tiles.render(16, 37308, 18968, layer="satellite")
    with pytest.raises(motif.OptionError, match="2\\^16"):
        tiles.render(16, 70000, 18968)
    with pytest.raises(OSError, match="nothing.osm.pbf"):
        motif.tiles(ROOT / "nothing.osm.pbf")


def test_render_tiles_on_dask_packs_the_clis_archive(cli, tmp_path):
    """A pyramid rendered as Dask tasks on a LocalCluster (two worker processes, the tile set
    scattered to each) is byte for byte the archive of `motif tiles render`."""
    cli(["--seed", "4", "tiles", "render", "--map", MAP, "--zoom", "15-16", "--band", "3", "--out", "cli.pmtiles"], tmp_path)
    from dask.distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            tiles = motif.batch.render_tiles(MAP, (15, 16), tmp_path / "dask.pmtiles", client=client, seed=4, band=3)
    assert len(tiles) == 24 + 9
    assert (tmp_path / "dask.pmtiles").read_bytes() == (tmp_path / "cli.pmtiles").read_bytes()
