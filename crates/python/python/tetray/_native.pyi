"""Type stub of the native module (crates/python/src). Use the functions
of the ``tetray`` package; these are its building blocks."""

from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

DEFAULT_VIEW: Tuple[float, float]

def methods() -> List[str]: ...

class Grid:
    @staticmethod
    def unstructured(
        points: npt.NDArray[np.float64],
        connectivity: npt.NDArray[np.int64],
        offsets: npt.NDArray[np.int64],
        celltypes: npt.NDArray[np.int64],
        point_data: Dict[str, npt.NDArray[np.float64]],
        cell_data: Dict[str, npt.NDArray[np.float64]],
        name: str,
    ) -> "Grid": ...
    @staticmethod
    def structured(
        dims: Tuple[int, int, int],
        points: npt.NDArray[np.float64],
        point_data: Dict[str, npt.NDArray[np.float64]],
        cell_data: Dict[str, npt.NDArray[np.float64]],
        dataset: str,
        name: str,
    ) -> "Grid": ...

Camera = Dict[str, Any]
Image = npt.NDArray[np.float32]

class Scene:
    def __init__(
        self,
        mesh: Union[str, Grid],
        *,
        scalars: Optional[str] = None,
        size: Tuple[int, int] = (512, 512),
        integrator: str = "ppi",
        renderer: str = "auto",
        camera: Optional[Camera] = None,
        tf_json: Optional[str] = None,
        tf_name: Optional[str] = None,
        tf_rescale: bool = True,
        tf_points: Optional[Tuple[Sequence[Tuple[float, float, float, float]], Sequence[Tuple[float, float]]]] = None,
        clim: Optional[Tuple[float, float]] = None,
        unit_distance: Optional[float] = None,
        opacity_mode: str = "exact",
        early_termination: float = 1.0,
        max_steps: Optional[int] = None,
        linearize: str = "subdivide",
        q: Optional[str] = None,
        time_step: Optional[int] = None,
        time: Optional[float] = None,
        block: Optional[str] = None,
        psi_size: int = 1024,
    ) -> None: ...
    def render(self, camera: Optional[Camera] = None, size: Optional[Tuple[int, int]] = None) -> Image: ...
    def orbit(self, frames: int, step: Optional[float] = None) -> List[Image]: ...
    def compare(
        self, specs: Sequence[Tuple[str, Optional[str], Optional[str]]], frames: int = 1
    ) -> Tuple[str, Image, List[Image]]: ...
    @property
    def info(self) -> Dict[str, Any]: ...
    @property
    def camera(self) -> Camera: ...
    def to_html(
        self, background: List[float], bench: Optional[Tuple[int, int]] = None, folder: bool = False
    ) -> Tuple[str, Optional[str]]: ...
    def take_log(self) -> Tuple[List[str], List[str]]: ...

def segment(
    integrator: str,
    lb: Tuple[float, float, float],
    lf: Tuple[float, float, float],
    tau_b: Tuple[float, float, float],
    tau_f: Tuple[float, float, float],
    length: float,
    incoming: Tuple[float, float, float] = (0.0, 0.0, 0.0),
    unit_distance: float = 1.0,
    psi_size: int = 1024,
    riemann_step: Optional[float] = None,
    preintegration_size: int = 256,
) -> Dict[str, Any]: ...
def psi(gamma_b: float, gamma_f: float, size: int = 1024) -> Dict[str, Any]: ...
