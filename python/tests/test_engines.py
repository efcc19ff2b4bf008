"""Every engine from Python on small real inputs: the same bytes as the CLI for the same seed,
the GIL released while the engine works, and clear exceptions for bad arguments."""

import json
import threading
import time

import numpy as np
import pytest

import motif
from conftest import ROOT, grey_guide

CURVE = ROOT / "data" / "real" / "curve"
POINTS = ROOT / "data" / "real" / "points"


def test_texture_equals_the_cli(cli, tmp_path, photo):
    exemplar = np.ascontiguousarray(photo[40:104, 40:104, :3])
    motif.write_png(str(tmp_path / "exemplar.png"), exemplar)
    cli(["--seed", "5", "texture", "--exemplar", "exemplar.png", "--size", "96x80", "--out", "out.png"], tmp_path)
    image, report = motif.texture(exemplar, (96, 80), seed=5, report=True)
    assert image.shape == (80, 96, 4) and image.dtype == np.uint8
    assert np.array_equal(image, motif.read_image(str(tmp_path / "out.png")))
    assert report["output_size"] == [96, 80] and report["estimated_memory_bytes"] > 0


def test_stylize_equals_the_cli_and_takes_weights(cli, tmp_path, photo):
    style = np.ascontiguousarray(photo[:96, :96, :3])
    source = grey_guide(style)
    target = grey_guide(np.ascontiguousarray(photo[100:180, 60:160, :3]))
    for name, array in (("A1.png", style), ("A.png", source), ("B.png", target)):
        motif.write_png(str(tmp_path / name), array)
    cli(["--seed", "3", "stylize", "--style", "A1.png", "--guide", "A.png", "B.png", "--out", "B1.png"], tmp_path)
    image = motif.stylize(style, [(source, target)], seed=3)
    assert image.shape == (80, 100, 4)
    assert np.array_equal(image, motif.read_image(str(tmp_path / "B1.png")))
    # A weighted pair and an option by its flag name run too.
    weighted = motif.stylize(style, [(source, target, 2.0)], seed=3, patch_size=7)
    assert weighted.shape == image.shape


def segment_guide(image, levels=3):
    """The image's luminance in `levels` flat grey segments, as an H×W×3 guide."""
    grey = grey_guide(image)[:, :, 0].astype(np.int32)
    bands = np.minimum(grey * levels // 256, levels - 1)
    flat = (bands * (255 // (levels - 1))).astype(np.uint8)
    return np.repeat(flat[:, :, None], 3, axis=2)


def test_presynth_and_band_stylize_equal_the_cli(cli, tmp_path, photo):
    style = np.ascontiguousarray(photo[:96, :96, :3])
    source = segment_guide(style)
    target = segment_guide(np.ascontiguousarray(photo[100:180, 60:160, :3]))
    for name, array in (("A1.png", style), ("A.png", source), ("B.png", target)):
        motif.write_png(str(tmp_path / name), array)
    cli(["--seed", "3", "presynth", "--style", "A1.png", "--guide", "A.png", "--size", "64x64", "--out-dir", "tex"], tmp_path)
    arguments = ["stylize", "--style", "A1.png", "--guide", "A.png", "B.png", "--presynth", "tex", "--out", "B1.png"]
    cli(["--seed", "3"] + arguments, tmp_path)
    textures, report = motif.presynth(style, source, (64, 64), seed=3, report=True)
    assert len(textures) == report["segments"] == len(np.unique(source[:, :, 0])) and report["texture_size"] == [64, 64]
    assert sorted(c[0] for c in textures.colours()) == sorted(np.unique(source[:, :, 0]).tolist())
    manifest = json.loads((tmp_path / "tex" / "presynth.json").read_text())
    for colour, image, entry in zip(textures.colours(), textures.images(), manifest["segments"]):
        assert entry["colour"] == "#" + "".join(f"{v:02x}" for v in colour)
        assert np.array_equal(image, motif.read_image(str(tmp_path / "tex" / entry["file"])))
    image = motif.stylize(style, [(source, target)], textures=textures, seed=3)
    assert np.array_equal(image, motif.read_image(str(tmp_path / "B1.png")))
    with pytest.raises(TypeError, match="presynth"):
        motif.stylize(style, [(source, target)], textures=[image])


def test_every_job_is_a_function_and_a_command(cli, tmp_path):
    """`motif.jobs()` lists motif-jobs' JOBS: each is a function here and a `motif` command with its summary."""
    names = [name for name, _ in motif.jobs()]
    assert names == ["curve", "points", "strokes", "stylize", "presynth", "texture", "inpaint", "zoom", "video", "tiles"]
    for name, summary in motif.jobs():
        assert name in motif.__all__ and callable(getattr(motif, name)), name
        assert summary in cli([name, "--help"], tmp_path).stdout, name
        assert set(motif.options(name)) <= {flag.replace("-", "_") for flag in motif._motif.options(name)}


def test_curve_equals_the_cli(cli, tmp_path):
    exemplar = motif.read_image(str(CURVE / "chain_small.png"))
    t = np.linspace(0.0, 1.0, 40)
    path = np.stack([30 + 340 * t, 120 + 60 * np.sin(2.5 * np.pi * t)], axis=1)
    (tmp_path / "path.csv").write_text("x,y\n" + "".join(f"{float(x)!r},{float(y)!r}\n" for x, y in path))
    arguments = ["curve", "--exemplar", str(CURVE / "chain_small.png"), "--path", "path.csv", "--width", "82"]
    cli(arguments + ["--piece-length", "24", "--out", "out.png", "--pieces", "pieces.json"], tmp_path)
    image, pieces = motif.curve(exemplar, path, 82, 24)
    assert np.array_equal(image, motif.read_image(str(tmp_path / "out.png")))
    assert pieces == json.loads((tmp_path / "pieces.json").read_text())["pieces"]
    assert len(pieces) > 10


def test_curve_tile_images_equal_the_cli(cli, tmp_path):
    """A cap from an image of its own (the chain's first link cut out), as --start-tile-image and
    --end-tile-image: the same bytes as the CLI, and the caps drawn from it."""
    exemplar = motif.read_image(str(CURVE / "chain_small.png"))
    link = np.ascontiguousarray(exemplar[:, :40])
    motif.write_png(str(tmp_path / "link.png"), link)
    t = np.linspace(0.0, 1.0, 40)
    path = np.stack([30 + 340 * t, 120 + 60 * np.sin(2.5 * np.pi * t)], axis=1)
    (tmp_path / "path.csv").write_text("x,y\n" + "".join(f"{float(x)!r},{float(y)!r}\n" for x, y in path))
    arguments = ["curve", "--exemplar", str(CURVE / "chain_small.png"), "--path", "path.csv", "--width", "82"]
    tiles = ["--start-tile-image", "link.png", "--end-tile-image", "link.png"]
    cli(arguments + ["--piece-length", "24", "--out", "out.png"] + tiles, tmp_path)
    image, pieces = motif.curve(exemplar, path, 82, 24, start_tile_image=link, end_tile_image=link)
    assert np.array_equal(image, motif.read_image(str(tmp_path / "out.png")))
    assert (pieces[0]["exemplar"], pieces[-1]["exemplar"]) == (1, 2)
    assert all(piece["exemplar"] == 0 for piece in pieces[1:-1])


def test_points_equal_the_cli(cli, tmp_path):
    arguments = ["points", "--exemplar", str(POINTS / "swedishpines.csv"), "--neighbourhood", "32"]
    cli(["--seed", "4"] + arguments + ["--exemplar-window", "96,100", "--domain", "box:140,120", "--out", "out.csv"], tmp_path)
    exemplar = motif.read_points(str(POINTS / "swedishpines.csv"))
    result = motif.points(exemplar, 32, domain=(140, 120), exemplar_window=[96, 100], seed=4)
    written = motif.read_points(str(tmp_path / "out.csv"))
    assert sorted(result) == sorted(written)
    for name in written:
        assert np.array_equal(result[name], written[name]), name


def test_points_keep_labels_as_integers(cli):
    exemplar = motif.read_points(str(POINTS / "amacrine.csv"))
    assert exemplar["label"].dtype == np.int64
    result = motif.points(exemplar, 0.17, domain=(1.2, 0.8), exemplar_window=[1.6012084592, 1.0], seed=2)
    assert result["label"].dtype == np.int64
    assert set(np.unique(result["label"])) <= {0, 1}


def test_strokes_equal_the_cli(cli, tmp_path):
    reference = (ROOT / "data" / "real" / "curve" / "letter_s.svg").read_text()
    (tmp_path / "reference.svg").write_text(reference)
    cli(["strokes", "--reference", "reference.svg", "--scale", "30", "--rect", "400,300", "--out", "out.svg"], tmp_path)
    svg, report = motif.strokes(reference, 30, rect=(400, 300), report=True)
    assert svg == (tmp_path / "out.svg").read_text()
    assert report["output_elements"] >= 1
    # The flattening tolerance's default and range are the CLI's (one declaration).
    assert motif.strokes(reference, 30, rect=(400, 300), tolerance=0.1) == svg
    with pytest.raises(motif.OptionError, match="tolerance"):
        motif.strokes(reference, 30, rect=(400, 300), tolerance=0)


def test_strokes_infer_the_scale_as_the_cli(cli, tmp_path):
    reference = (ROOT / "data" / "real" / "strokes" / "cactus_spines_cropped.svg").read_text()
    (tmp_path / "reference.svg").write_text(reference)
    cli(["strokes", "--reference", "reference.svg", "--rect", "460,460", "--out", "out.svg"], tmp_path)
    svg, report = motif.strokes(reference, rect=(460, 460), report=True)
    assert svg == (tmp_path / "out.svg").read_text()
    assert report["scale_inferred"] is True and report["scale_inference"]["method"] == "gap"
    assert report["scale_inference"]["below"] < report["scale"] < report["scale_inference"]["above"]
    assert report["reference_elements"] == 57
    given = motif.strokes(reference, 6, rect=(460, 460), report=True)[1]
    assert (given["scale"], given["scale_inferred"], given["scale_inference"]) == (6, False, None)
    assert motif.strokes(reference, None, rect=(460, 460)) == svg


def test_a_call_releases_the_gil(photo):
    exemplar = np.ascontiguousarray(photo[:64, :64, :3])
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.002)

    ticker = threading.Thread(target=tick)
    ticker.start()
    start = time.perf_counter()
    motif.texture(exemplar, (384, 384), seed=1, threads=1)
    end = time.perf_counter()
    stop.set()
    ticker.join()
    during = [t for t in ticks if start < t < end]
    # Holding the GIL for the whole call would leave the ticker silent until it returned.
    assert end - start > 0.05
    assert len(during) >= 5, f"{len(during)} ticks in {end - start:.2f} s"


def test_bad_arguments_raise_clear_exceptions(photo):
    exemplar = np.ascontiguousarray(photo[:32, :32, :3])
    with pytest.raises(ValueError, match="uint8"):
        motif.texture(exemplar.astype(np.float32), (32, 32))
    with pytest.raises(ValueError, match="shape"):
        motif.texture(np.zeros((4, 4, 2), dtype=np.uint8), (32, 32))
    with pytest.raises(ValueError, match="size"):
        motif.texture(exemplar, (-5, 32))
    with pytest.raises(TypeError, match="patchsize"):
        motif.texture(exemplar, (32, 32), patchsize=3)
    with pytest.raises(ValueError, match="patch-size"):
        motif.texture(exemplar, (32, 32), patch_size=4)
    with pytest.raises(ValueError, match="uniformity = nan"):
        motif.texture(exemplar, (32, 32), uniformity=float("nan"))
    with pytest.raises(ValueError, match="max-memory"):
        motif.texture(exemplar, (4096, 4096), max_memory="64M")
    path = np.array([[0.0, 0.0], [100.0, float("nan")], [200.0, 0.0]])
    with pytest.raises(ValueError, match="path"):
        motif.curve(exemplar, path, 20, 10)
    with pytest.raises(ValueError, match="neighbourhood"):
        motif.points({"x": [0.0, 1.0, 2.0, 0.5], "y": [0.0, 1.0, 0.0, 2.0]}, -1.0, domain=(5, 5))
    with pytest.raises(ValueError, match="x and y"):
        motif.points({"u": [0.0, 1.0, 2.0]}, 1.0, domain=(5, 5))
    with pytest.raises(ValueError, match="target"):
        motif.strokes("<svg/>", 10)
    with pytest.raises(OSError, match="missing.png"):
        motif.read_image("missing.png")


def test_options_list_the_cli_flags():
    assert "patch_size" in motif.options("texture")
    assert "exemplar_window" in motif.options("points")
    assert "pieces_shape" in motif.options("curve")


def test_every_declared_option_is_a_keyword():
    """The typed options rendered from motif-jobs' declarations are exactly the keywords taken."""
    from motif import _options

    for name, declared in vars(_options).items():
        if not name.endswith("Options") or name == "TypedDict":
            continue
        engine = name[: -len("Options")].lower()
        # Every name the job takes, keywords and the positional arguments alike.
        keywords = {flag.replace("-", "_") for flag in motif._motif.options(engine)}
        assert set(declared.__annotations__) <= keywords, (engine, set(declared.__annotations__) - keywords)


def test_strokes_maps_equal_the_cli(cli, tmp_path):
    strokes_dir = ROOT / "data" / "real" / "strokes"
    reference = (strokes_dir / "arkansas_stars.svg").read_text()
    (tmp_path / "reference.svg").write_text(reference)
    photo = str(strokes_dir / "photo_astronaut.png")
    cli(["strokes", "--reference", "reference.svg", "--scale", "5", "--rect", "900,900",
         "--density-map", photo, "--out", "out.svg"], tmp_path)
    face = motif.read_image(photo)
    svg, report = motif.strokes(reference, 5, rect=(900, 900), density_map=face, report=True)
    assert svg == (tmp_path / "out.svg").read_text()
    uniform = motif.strokes(reference, 5, rect=(900, 900), report=True)[1]
    assert report["output_elements"] < uniform["output_elements"]
    with pytest.raises(ValueError, match="density-map"):
        motif.strokes(reference, 5, rect=(900, 450), density_map=face)
    with pytest.raises(ValueError, match="uint8"):
        motif.strokes(reference, 5, rect=(900, 900), density_map=face.astype(np.float32))


def test_points_maps_equal_the_cli(cli, tmp_path):
    ramp = np.tile(np.linspace(0, 255, 96).astype(np.uint8), (100, 1))
    motif.write_png(str(tmp_path / "ramp.png"), ramp)
    cli(["points", "--exemplar", str(POINTS / "swedishpines.csv"), "--neighbourhood", "32", "--domain", "box:192,200",
         "--exemplar-window", "96,100", "--rotation-map", "ramp.png", "--out", "out.csv"], tmp_path)
    pines = motif.read_points(str(POINTS / "swedishpines.csv"))
    result = motif.points(pines, 32, domain=(192, 200), exemplar_window=[96, 100], rotation_map=ramp)
    expected = motif.read_points(str(tmp_path / "out.csv"))
    assert np.allclose(result["x"], expected["x"], rtol=0, atol=1e-9)
    assert np.allclose(result["y"], expected["y"], rtol=0, atol=1e-9)
    with pytest.raises(ValueError, match="rotation-map"):
        motif.points(pines, 32, domain=(400, 200), exemplar_window=[96, 100], rotation_map=ramp)


def test_points_on_a_mesh_surface_equal_the_cli(cli, tmp_path):
    # An octahedron |x − 4| + |y − 4| + |z − 4| = 4: its surface holds the Swedish pines scaled
    # to its size (a 2D exemplar on a surface gives 3D points on it).
    vertices = np.array([[8, 4, 4], [0, 4, 4], [4, 8, 4], [4, 0, 4], [4, 4, 8], [4, 4, 0]], dtype=np.float64)
    triangles = np.array([[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]])
    obj = "".join(f"v {x:g} {y:g} {z:g}\n" for x, y, z in vertices) + "".join(
        f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in triangles
    )
    (tmp_path / "solid.obj").write_text(obj)
    pines = motif.read_points(str(POINTS / "swedishpines.csv"))
    small = {"x": pines["x"] / 10, "y": pines["y"] / 10}
    lines = ["x,y"] + [f"{float(x)!r},{float(y)!r}" for x, y in zip(small["x"], small["y"])]
    (tmp_path / "small.csv").write_text("\n".join(lines) + "\n")
    cli(["points", "--exemplar", "small.csv", "--neighbourhood", "3.2", "--domain", "surface:solid.obj",
         "--surface-directions", "0,0,1", "--out", "out.csv"], tmp_path)
    expected = motif.read_points(str(tmp_path / "out.csv"))
    result, report = motif.points(
        motif.read_points(str(tmp_path / "small.csv")), 3.2, surface=(vertices, triangles), surface_directions=[0, 0, 1],
        report=True,
    )
    for axis in "xyz":
        assert np.allclose(result[axis], expected[axis], rtol=0, atol=1e-9)
    distance = np.abs(result["x"] - 4) + np.abs(result["y"] - 4) + np.abs(result["z"] - 4)
    assert np.all(np.abs(distance - 4) < 1e-6)
    assert abs(report["surface"]["area"] - 64 * np.sqrt(3)) < 1e-9
    with pytest.raises(ValueError, match="integer"):
        motif.points(small, 3.2, surface=(vertices, triangles.astype(np.float64)))
    with pytest.raises(ValueError, match="surface_directions"):
        motif.points(small, 3.2, surface=(vertices, triangles), surface_directions="along")
    with pytest.raises(ValueError, match="not finite, or is zero"):
        motif.points(small, 3.2, surface=(vertices, triangles), surface_directions=[0, 0, 0])


def test_inpaint_equals_the_cli_and_keeps_the_rest(cli, tmp_path):
    stone = motif.read_image(str(ROOT / "data" / "real" / "stylize" / "stone33.png"))
    height, width = stone.shape[:2]
    y, x = np.mgrid[0:height, 0:width]
    hole = (x - 78) ** 2 + (y - 70) ** 2 < 26**2
    motif.write_png(str(tmp_path / "hole.png"), np.where(hole[:, :, None], 255, 0).astype(np.uint8).repeat(3, axis=2))
    cli(["inpaint", "--image", str(ROOT / "data" / "real" / "stylize" / "stone33.png"), "--mask", "hole.png",
         "--out", "filled.png"], tmp_path)
    filled, report = motif.inpaint(stone, hole, report=True)
    assert np.array_equal(filled, motif.read_image(str(tmp_path / "filled.png")))
    assert np.array_equal(filled[~hole], stone[~hole])
    assert report["searched_pixels"] < height * width
    with pytest.raises(ValueError, match="bool"):
        motif.inpaint(stone, hole.astype(np.uint8))
    with pytest.raises(ValueError, match="size"):
        motif.inpaint(stone, hole[:-1])
    with pytest.raises(ValueError, match="no pixel"):
        motif.inpaint(stone, np.zeros_like(hole))


def test_zoom_equals_the_cli(cli, tmp_path):
    stone = ROOT / "data" / "real" / "stylize" / "stone33.png"
    cli(["zoom", "--exemplar", str(stone), "--size", "64x48", "--levels", "3", "--out-dir", "levels"], tmp_path)
    levels, reports = motif.zoom(motif.read_image(str(stone)), (64, 48), levels=3, report=True)
    assert len(levels) == 3 and len(reports) == 3
    for index, level in enumerate(levels):
        assert level.shape == (48, 64, 4)
        assert np.array_equal(level, motif.read_image(str(tmp_path / "levels" / f"zoom-{index + 1:02d}.png")))
    with pytest.raises(ValueError, match="invalid factor"):
        motif.zoom(motif.read_image(str(stone)), (64, 48), factor=30)


def test_video_equals_the_cli_and_checks_its_inputs(cli, tmp_path, photo):
    frames = [np.ascontiguousarray(photo[30 : 30 + 48, 5 * i : 5 * i + 64, :3]) for i in range(4)]
    key = np.ascontiguousarray(255 - frames[0])
    (tmp_path / "in").mkdir()
    (tmp_path / "out").mkdir()
    for index, frame in enumerate(frames):
        motif.write_png(str(tmp_path / "in" / f"{index:03d}.png"), frame)
    motif.write_png(str(tmp_path / "key.png"), key)
    cli(["--seed", "4", "video", "--frames", "in/%03d.png", "--key", "0:key.png", "--out", "out/%03d.png"], tmp_path)
    images, report = motif.video(frames, {0: key}, seed=4, report=True)
    assert len(images) == 4 and report["frames"] == 4 and report["flicker"] > 0
    for index, image in enumerate(images):
        assert np.array_equal(image, motif.read_image(str(tmp_path / "out" / f"{index:03d}.png"))), index
    with pytest.raises(ValueError, match="keyframe 7"):
        motif.video(frames, {7: key})
    with pytest.raises(ValueError, match="temporal-weight"):
        motif.video(frames, {0: key}, temporal_weight=-1)
    with pytest.raises(ValueError, match="mask"):
        motif.video(frames, {0: key}, mask=np.ones((3, 3), dtype=bool))
    with pytest.raises(TypeError, match="temporal_weight"):
        motif.video(frames, {0: key}, temporal_wieght=1)


def test_errors_come_in_kinds(photo):
    """A bad option, an unusable input and a run past a limit each raise their own ValueError."""
    exemplar = np.ascontiguousarray(photo[:64, :64, :3])
    with pytest.raises(motif.OptionError, match="patch-size"):
        motif.texture(exemplar, (32, 32), patch_size=4)
    with pytest.raises(motif.InputError):
        motif.points({"x": np.array([0.0, 1.0]), "y": np.array([0.0, 1.0])}, 1.0, domain=(10, 10))
    with pytest.raises(motif.LimitError):
        motif.texture(exemplar, (4096, 4096), max_memory="1M")
    with pytest.raises(MemoryError, match="memory"):
        motif.texture(exemplar, (4096, 4096), max_memory="1M")
    for kind in (motif.OptionError, motif.InputError, motif.LimitError):
        assert issubclass(kind, motif.MotifError) and issubclass(kind, ValueError)
    assert issubclass(motif.LimitError, MemoryError) and not issubclass(motif.OptionError, MemoryError)
    with pytest.raises(OSError):
        motif.read_points("no/such/points.csv")
