"""Type stubs of motif's Python API (see motif/__init__.py for the documentation)."""

from typing import Any, Dict, Iterable, List, Literal, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt
from typing_extensions import Unpack

from motif._options import PointsOptions, PresynthOptions

ImageArray = npt.NDArray[np.uint8]
PointData = Union[npt.ArrayLike, Dict[str, npt.ArrayLike]]

@overload
def texture(
    exemplar: npt.ArrayLike, size: Tuple[int, int], *, seed: int = ..., threads: Optional[int] = ...,
    report: Literal[False] = ..., **options: Any
) -> ImageArray: ...
@overload
def texture(
    exemplar: npt.ArrayLike, size: Tuple[int, int], *, seed: int = ..., threads: Optional[int] = ...,
    report: Literal[True], **options: Any
) -> Tuple[ImageArray, Dict[str, Any]]: ...
@overload
def zoom(
    exemplar: npt.ArrayLike, size: Tuple[int, int], *, factor: float = ..., levels: int = ..., seed: int = ...,
    threads: Optional[int] = ..., report: Literal[False] = ..., **options: Any
) -> List[ImageArray]: ...
@overload
def zoom(
    exemplar: npt.ArrayLike, size: Tuple[int, int], *, factor: float = ..., levels: int = ..., seed: int = ...,
    threads: Optional[int] = ..., report: Literal[True], **options: Any
) -> Tuple[List[ImageArray], List[Dict[str, Any]]]: ...
@overload
def inpaint(
    image: npt.ArrayLike, hole: npt.ArrayLike, *, seed: int = ..., threads: Optional[int] = ...,
    report: Literal[False] = ..., **options: Any
) -> ImageArray: ...
@overload
def inpaint(
    image: npt.ArrayLike, hole: npt.ArrayLike, *, seed: int = ..., threads: Optional[int] = ...,
    report: Literal[True], **options: Any
) -> Tuple[ImageArray, Dict[str, Any]]: ...
@overload
def video(
    frames: Sequence[npt.ArrayLike], keyframes: Dict[int, npt.ArrayLike], *, mask: Optional[npt.ArrayLike] = ...,
    seed: int = ..., threads: Optional[int] = ..., report: Literal[False] = ..., **options: Any
) -> List[ImageArray]: ...
@overload
def video(
    frames: Sequence[npt.ArrayLike], keyframes: Dict[int, npt.ArrayLike], *, mask: Optional[npt.ArrayLike] = ...,
    seed: int = ..., threads: Optional[int] = ..., report: Literal[True], **options: Any
) -> Tuple[List[ImageArray], Dict[str, Any]]: ...
@overload
def stylize(
    style: npt.ArrayLike, guides: Sequence[Sequence[Any]], *, textures: Optional[Textures] = ..., seed: int = ...,
    threads: Optional[int] = ..., report: Literal[False] = ..., **options: Any
) -> ImageArray: ...
@overload
def stylize(
    style: npt.ArrayLike, guides: Sequence[Sequence[Any]], *, textures: Optional[Textures] = ..., seed: int = ...,
    threads: Optional[int] = ..., report: Literal[True], **options: Any
) -> Tuple[ImageArray, Dict[str, Any]]: ...
class Textures:
    """Pre-synthesized textures, one per segment colour (``presynth``'s result, for ``stylize``)."""
    def __len__(self) -> int: ...
    def colours(self) -> List[List[int]]: ...
    def images(self) -> List[ImageArray]: ...
@overload
def presynth(
    style: npt.ArrayLike, guide: npt.ArrayLike, size: Optional[Tuple[int, int]] = ..., *, seed: int = ...,
    threads: Optional[int] = ..., report: Literal[False] = ..., **options: Unpack[PresynthOptions]
) -> Textures: ...
@overload
def presynth(
    style: npt.ArrayLike, guide: npt.ArrayLike, size: Optional[Tuple[int, int]] = ..., *, seed: int = ...,
    threads: Optional[int] = ..., report: Literal[True], **options: Unpack[PresynthOptions]
) -> Tuple[Textures, Dict[str, Any]]: ...
@overload
def curve(
    exemplar: npt.ArrayLike, path: npt.ArrayLike, width: float, piece_length: float, *,
    more_exemplars: Iterable[npt.ArrayLike] = ..., avoid: Optional[npt.ArrayLike] = ...,
    start_tile_image: Optional[npt.ArrayLike] = ..., end_tile_image: Optional[npt.ArrayLike] = ...,
    corner_tile_image: Optional[npt.ArrayLike] = ..., seed: int = ...,
    threads: Optional[int] = ..., report: Literal[False] = ..., **options: Any
) -> Tuple[ImageArray, List[Dict[str, Any]]]: ...
@overload
def curve(
    exemplar: npt.ArrayLike, path: npt.ArrayLike, width: float, piece_length: float, *,
    more_exemplars: Iterable[npt.ArrayLike] = ..., avoid: Optional[npt.ArrayLike] = ...,
    start_tile_image: Optional[npt.ArrayLike] = ..., end_tile_image: Optional[npt.ArrayLike] = ...,
    corner_tile_image: Optional[npt.ArrayLike] = ..., seed: int = ...,
    threads: Optional[int] = ..., report: Literal[True], **options: Any
) -> Tuple[Tuple[ImageArray, List[Dict[str, Any]]], Dict[str, Any]]: ...
@overload
def points(
    exemplar: PointData, neighbourhood: Optional[float] = ..., *, domain: Any = ..., along: Optional[npt.ArrayLike] = ...,
    brush_width: Optional[float] = ..., scale_along: Optional[Tuple[float, float]] = ...,
    volume: Optional[Tuple[npt.ArrayLike, npt.ArrayLike]] = ...,
    surface: Optional[Tuple[npt.ArrayLike, npt.ArrayLike]] = ..., surface_directions: Any = ...,
    existing: Optional[PointData] = ..., rotation_map: Optional[npt.ArrayLike] = ...,
    scale_map: Optional[npt.ArrayLike] = ..., seed: int = ..., threads: Optional[int] = ...,
    report: Literal[False] = ..., **options: Unpack[PointsOptions]
) -> Dict[str, np.ndarray]: ...
@overload
def points(
    exemplar: PointData, neighbourhood: Optional[float] = ..., *, domain: Any = ..., along: Optional[npt.ArrayLike] = ...,
    brush_width: Optional[float] = ..., scale_along: Optional[Tuple[float, float]] = ...,
    volume: Optional[Tuple[npt.ArrayLike, npt.ArrayLike]] = ...,
    surface: Optional[Tuple[npt.ArrayLike, npt.ArrayLike]] = ..., surface_directions: Any = ...,
    existing: Optional[PointData] = ..., rotation_map: Optional[npt.ArrayLike] = ...,
    scale_map: Optional[npt.ArrayLike] = ..., seed: int = ..., threads: Optional[int] = ...,
    report: Literal[True], **options: Unpack[PointsOptions]
) -> Tuple[Dict[str, np.ndarray], Dict[str, Any]]: ...
@overload
def strokes(
    reference_svg: str, scale: Optional[float] = ..., *, rect: Optional[Tuple[float, float]] = ...,
    along: Optional[npt.ArrayLike] = ..., region: Optional[npt.ArrayLike] = ...,
    size: Optional[Tuple[float, float]] = ..., tolerance: Optional[float] = ...,
    density_map: Optional[npt.ArrayLike] = ..., scale_map: Optional[npt.ArrayLike] = ..., seed: int = ...,
    threads: Optional[int] = ..., report: Literal[False] = ..., **options: Any
) -> str: ...
@overload
def strokes(
    reference_svg: str, scale: Optional[float] = ..., *, rect: Optional[Tuple[float, float]] = ...,
    along: Optional[npt.ArrayLike] = ..., region: Optional[npt.ArrayLike] = ...,
    size: Optional[Tuple[float, float]] = ..., tolerance: Optional[float] = ...,
    density_map: Optional[npt.ArrayLike] = ..., scale_map: Optional[npt.ArrayLike] = ..., seed: int = ...,
    threads: Optional[int] = ..., report: Literal[True], **options: Any
) -> Tuple[str, Dict[str, Any]]: ...
def read_image(path: str) -> ImageArray: ...
def write_png(path: str, image: npt.ArrayLike) -> None: ...
def read_points(path: str) -> Dict[str, np.ndarray]: ...
def options(engine: str) -> List[str]: ...
def jobs() -> List[Tuple[str, str]]: ...
class MotifError(ValueError): ...
class OptionError(MotifError): ...
class InputError(MotifError): ...
class LimitError(MotifError, MemoryError): ...
