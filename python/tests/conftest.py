"""Shared fixtures: the repository's real data and the built `motif` binary."""

import os
import pathlib
import subprocess

import numpy as np
import pytest

import motif

ROOT = pathlib.Path(__file__).resolve().parents[2]
BINARY = pathlib.Path(os.environ.get("MOTIF_BIN", ROOT / "target" / "release" / "motif"))


@pytest.fixture(scope="session")
def cli():
    """Runs the `motif` binary (build it with `cargo build --release` first; MOTIF_BIN overrides)."""
    if not BINARY.is_file():
        pytest.fail(f"the motif binary is not built at {BINARY}: run `cargo build --release` (or set MOTIF_BIN)")

    def run(arguments, cwd):
        result = subprocess.run([str(BINARY), "--quiet", *map(str, arguments)], cwd=cwd, capture_output=True, text=True)
        assert result.returncode == 0, result.stderr
        return result

    return run


@pytest.fixture(scope="session")
def photo():
    """A real photo (chain mail, 200 × 200, data/real/points) as H×W×4 uint8."""
    return motif.read_image(str(ROOT / "data" / "real" / "points" / "chain_contours_source.png"))


def grey_guide(image):
    """The luminance of an image as an H×W×3 guide."""
    grey = (0.299 * image[:, :, 0] + 0.587 * image[:, :, 1] + 0.114 * image[:, :, 2]).round().astype(np.uint8)
    return np.repeat(grey[:, :, None], 3, axis=2)
