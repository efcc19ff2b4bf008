"""Type stubs of motif.batch (see batch.py for the documentation)."""

from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np

def tile_grid(
    height: int, width: int, tile: int, overlap: int
) -> List[Tuple[Tuple[int, int], Tuple[int, int, int, int], Tuple[int, int, int, int]]]: ...
def stylize_tiles(
    style: np.ndarray, guides: Sequence[Sequence[Any]], *, tile: int = ..., overlap: Optional[int] = ...,
    client: Any = ..., threads: int = ..., seed: int = ..., out: Optional[str] = ...,
    task: Callable[..., np.ndarray] = ..., **options: Any
) -> np.ndarray: ...
def stylize_frames(
    frames: Sequence[np.ndarray], keyframes: Dict[int, np.ndarray], *, client: Any = ..., threads: int = ...,
    seed: int = ..., mask: Optional[np.ndarray] = ..., **options: Any
) -> List[np.ndarray]: ...
def seam_error(image: np.ndarray, tile: int) -> float: ...
