"""Issue 13's treatment for the Python package: random and hostile arguments to every function
end in a result or a clear Python exception (ValueError, TypeError, OSError), never a crash of
the interpreter, a hang or a giant allocation. Fixed seeds; a few seconds in all."""

import numpy as np
import pytest

import motif

ALLOWED = (ValueError, TypeError, OSError)

AWKWARD_NUMBERS = [0, -1, 1e-300, 1e300, float("nan"), float("inf"), 3, 7, 2**63, -(2**70), 0.5]
AWKWARD_VALUES = AWKWARD_NUMBERS + ["", "8G", "exact", "nope", None, [], [1, 2, 3], {"a": 1}, True]


def random_array(rng):
    dtype = rng.choice([np.uint8, np.uint8, np.uint8, np.float32, np.int64, np.bool_])
    shape = [int(v) for v in rng.integers(0, 40, size=rng.integers(0, 5))]
    return (rng.random(shape) * 255).astype(dtype)


def random_options(rng, engine):
    names = motif.options(engine) + ["not_an_option"]
    picked = rng.choice(names, size=rng.integers(0, 4), replace=False)
    return {str(name): AWKWARD_VALUES[rng.integers(len(AWKWARD_VALUES))] for name in picked}


def attempt(function, *arguments, **options):
    try:
        function(*arguments, **options)
    except ALLOWED:
        pass


def test_random_images_and_options_give_results_or_clear_errors():
    rng = np.random.default_rng(20261202)
    for _ in range(120):
        exemplar = random_array(rng)
        size = tuple(int(v) for v in rng.integers(-4, 48, size=2))
        attempt(motif.texture, exemplar, size, threads=1, **random_options(rng, "texture"))
        guides = [(random_array(rng), random_array(rng)) for _ in range(rng.integers(0, 3))]
        attempt(motif.stylize, exemplar, guides, threads=1, **random_options(rng, "stylize"))


def test_random_curves_and_points_give_results_or_clear_errors():
    rng = np.random.default_rng(7)
    exemplar = np.zeros((16, 48, 4), dtype=np.uint8)
    exemplar[4:12, :, :] = 200
    for _ in range(80):
        path = rng.normal(scale=rng.choice([1e-3, 50.0, 1e9]), size=(int(rng.integers(0, 6)), int(rng.integers(1, 4))))
        width, piece = (AWKWARD_NUMBERS[i] for i in rng.integers(len(AWKWARD_NUMBERS), size=2))
        options = random_options(rng, "curve")
        options["max_memory"] = "64M"
        attempt(motif.curve, exemplar, path, width, piece, threads=1, **options)
        columns = {name: rng.normal(size=int(rng.integers(0, 30))) for name in rng.choice(["x", "y", "z", "dbh", "element"], size=3)}
        domain = tuple(AWKWARD_NUMBERS[i] for i in rng.integers(len(AWKWARD_NUMBERS), size=2))
        options = random_options(rng, "points")
        options["max_points"] = 2000
        attempt(motif.points, columns, AWKWARD_NUMBERS[rng.integers(len(AWKWARD_NUMBERS))], domain=domain, threads=1, **options)


def test_hostile_svg_and_files_give_clear_errors(tmp_path):
    for text in ["", "<svg", "<svg xmlns='http://www.w3.org/2000/svg'/>", "\x00\xff" * 10, "<!DOCTYPE x [<!ENTITY a 'a'>]><svg/>"]:
        with pytest.raises(ALLOWED):
            motif.strokes(text, 10.0, rect=(100, 100))
    (tmp_path / "bad.png").write_bytes(b"\x89PNG\r\n\x1a\n" + b"\x00" * 40)
    with pytest.raises(OSError, match="bad.png"):
        motif.read_image(str(tmp_path / "bad.png"))
    with pytest.raises(OSError):
        motif.read_points(str(tmp_path / "missing.ply"))
    with pytest.raises(OSError):
        motif.write_png(str(tmp_path / "no-such-folder" / "out.png"), np.zeros((4, 4, 3), dtype=np.uint8))
