"""Type stubs of haphe (the native module haphe._haphe)."""

from os import PathLike
from typing import Any, Dict, List, Literal, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str
# The largest force rendered unless told otherwise, newtons (the library's default).
DEFAULT_MAX_FORCE: float

_Path = Union[str, PathLike[str]]
_Vec3 = Union[Sequence[float], npt.NDArray[np.float64]]
_Rotation = Union[Sequence[float], Sequence[Sequence[float]], npt.NDArray[np.float64]]
# (N, 3) points: anything numpy.asarray(x, dtype=float64) takes (lists, float32, any strides).
_Points = npt.ArrayLike
_NonFinite = Literal["error", "skip"]

class HapheError(ValueError):
    """A file or an input haphe cannot use: the message names the file and the place."""

class DeviceError(OSError):
    """A device or its vendor library could not be opened, or the device failed: the
    message names the library, the variable that selects it and the SDK."""

def validate(
    path: _Path,
    units: str = "m",
    weld_tolerance: Optional[float] = None,
    self_intersections: bool = True,
) -> Dict[str, Any]:
    """The record of ``haphe validate --json`` for a mesh file, plus ``exit_code``."""

def allocations() -> Optional[int]:
    """Allocation calls of the Rust side so far; None unless built with count-allocations."""

def run(
    scene: Scene,
    device: Union[str, Sequence[str]] = "hand",
    seconds: float = 2.0,
    path: str = "explore",
    rate_hz: float = 1000.0,
    seed: int = 1,
    scale: Optional[Union[float, Sequence[float]]] = None,
    centre: Optional[Union[_Vec3, Sequence[_Vec3]]] = None,
    udp_timeout: float = 0.05,
    udp_workspace: float = 0.1,
    clutch_button: Optional[int] = None,
    presses: Optional[Sequence[Tuple[int, float, float]]] = None,
    tool_radius: Union[float, Sequence[float]] = 0.0,
) -> Union[Dict[str, Any], List[Dict[str, Any]]]:
    """Runs the servo loop with a device: "hand" (simulated, simulated clock), "dhd",
    "openhaptics" or "udp:HOST:PORT" (real, wall clock, mapped onto the scene), rendering
    the scene's textures and effects (a vibration above half ``rate_hz`` raises HapheError
    naming ``effect`` and its specification). Arrays t, hip, proxy, velocity, force,
    contact, object, triangle, penetration, buttons (uint32), clutch, one row per tick; offset (3,), how far the clutch moved the device's origin; strings
    device, stop and report (or None). While button ``clutch_button`` is held, the tool
    stays and the force fades out (a clutch); ``presses`` (button, from, until) holds
    buttons of the simulated hand. Raises DeviceError when the device or its library
    cannot be opened; Ctrl-C writes zero force, then raises KeyboardInterrupt. A list of
    devices ("dhd:0", "dhd:1", "openhaptics:NAME", ...) runs them in one scene on one
    servo, each with its own proxy, mapping and tool (``scale``, ``centre``, ``tool_radius``:
    one per device, as lists): a list of dicts, one per device; a fault of one stops all,
    named in stop."""

def check_deforming(
    scene: Scene,
    deformation: Literal["breathe", "dent", "breathe-dent", "twist"],
    path: _Points,
    rate_hz: float = 1000.0,
    tool_radius: float = 0.0,
) -> Dict[str, Union[int, float]]:
    """The library's check of the proxy against a brute-force proxy while the scene's
    first object deforms before every tick along ``path`` (one device point a tick):
    counts ticks, contact_ticks, mismatches, max_deviation (m), inside, bad_forces."""

class Shape:
    """A surface with its voxel map (object frame, metres)."""

    @staticmethod
    def from_file(
        path: _Path, units: str = "m", weld_tolerance: Optional[float] = None
    ) -> Shape: ...
    @staticmethod
    def from_arrays(vertices: _Points, faces: npt.NDArray[np.int64]) -> Shape: ...
    @staticmethod
    def load(path: _Path) -> Shape: ...
    def save(self, path: _Path) -> None: ...
    @staticmethod
    def from_bytes(data: bytes, name: Optional[str] = None) -> Shape:
        """A shape from its map file's bytes (to_bytes, save, haphe build), not rebuilt."""
    def to_bytes(self) -> bytes:
        """The map file's bytes; pickling a shape sends them."""
    def __reduce__(self) -> Tuple[Any, Tuple[bytes, str]]: ...
    def inside(self, points: _Points, nonfinite: _NonFinite = "error") -> npt.NDArray[np.bool_]:
        """(N, 3) points -> (N,) bool: inside the solid. A non-finite row raises
        HapheError naming it, or answers False with nonfinite="skip"."""
    def first_crossing(
        self,
        p0: _Points,
        p1: _Points,
        brute_force: bool = False,
        nonfinite: _NonFinite = "error",
    ) -> Dict[str, npt.NDArray[Any]]:
        """Arrays t (NaN none), triangle (-1 none), point, normal (N, 3), entering."""
    def sample_segments(
        self, kind: str, n: int, seed: int = 1
    ) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
        """n segments of a kind haphe verify tests: (p0, p1)."""
    def nearest(
        self, points: _Points, max_distance: float, nonfinite: _NonFinite = "error"
    ) -> Dict[str, npt.NDArray[Any]]:
        """Arrays distance (inf none), triangle (-1 none), point (N, 3)."""
    def arrays(self) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]:
        """(vertices (V, 3) float64, faces (F, 3) int64) in the surface's own order, the
        order Scene.deform takes (it may differ from the file's)."""
    @property
    def version(self) -> int:
        """How many deformations made this shape (0: never deformed)."""
    @property
    def triangles(self) -> int: ...
    @property
    def vertices(self) -> int: ...
    @property
    def is_solid(self) -> bool: ...
    @property
    def bounds(self) -> Tuple[Tuple[float, float, float], Tuple[float, float, float]]: ...

class Scene:
    """Shapes placed in the world with materials."""

    def __init__(self, capacity: int = 64) -> None: ...
    @staticmethod
    def from_gltf(
        path: _Path,
        units: str = "m",
        weld_tolerance: Optional[float] = None,
        capacity: Optional[int] = None,
        stiffness: float = 500.0,
        damping: float = 0.0,
        friction: float = 0.0,
        dynamic_friction: Optional[float] = None,
    ) -> Scene: ...
    @property
    def names(self) -> Dict[int, str]: ...
    def add(
        self,
        shape: Shape,
        position: _Vec3 = (0.0, 0.0, 0.0),
        rotation: Optional[_Rotation] = None,
        stiffness: float = 500.0,
        damping: float = 0.0,
        friction: float = 0.0,
        dynamic_friction: Optional[float] = None,
        two_sided: Optional[bool] = None,
        texture: Optional[str] = None,
    ) -> int:
        """The object's id. ``texture``: "sine:A:L" or "noise:A:L" (metres), None or ""
        for none; a refused one raises HapheError naming ``texture`` and it."""
    def move(self, id: int, position: _Vec3, rotation: Optional[_Rotation] = None) -> None: ...
    def remove(self, id: int) -> None: ...
    def deform(self, id: int, vertices: _Points, indices: Optional[npt.ArrayLike] = None) -> None:
        """Moves object id's vertices (V, 3) in the order of shape.arrays(), or with
        indices (K,) the vertices indices[k] to vertices[k] (K, 3); in force from the next
        tick. KeyError for an unknown id; HapheError naming the argument and the first bad
        row, the scene unchanged."""
    def shape(self, id: int) -> Shape:
        """Object id's shape as it is now (deformed, if it was); KeyError if unknown."""
    def set_texture(self, id: int, texture: Optional[str]) -> None:
        """Changes object id's texture (None or "": none); KeyError for an unknown id."""
    @property
    def textures(self) -> Dict[int, str]:
        """{id: specification} of the objects with a texture."""
    def add_effect(self, effect: str) -> None:
        """Adds a force effect ("vibration:FREQ:AMPLITUDE", "viscosity:B[:inside:ID |
        :box:X0:Y0:Z0:X1:Y1:Z1]", "spring:K:X:Y:Z", "magnet:DISTANCE:FORCE",
        "constant:FX:FY:FZ", "stick-slip[:K:FORCE]"), rendered by haphe.run; at most 16.
        A refused one raises HapheError naming ``effect`` and it."""
    @property
    def effects(self) -> List[str]:
        """The effects' specifications, in the order added."""
    def clear_effects(self) -> None: ...
    def replace(self, id: int, shape: Shape) -> None:
        """Gives object id a new version of its shape (Cutter.refresh's); KeyError for
        an unknown id, HapheError when shape is not a version of the object's."""
    def check_tool_radius(self, tool_radius: float) -> float:
        """tool_radius (m) if a tool of that radius fits the scene (0 to 0.5 m, at most
        the diagonal of the box bounding its objects); else raises HapheError."""
    def __len__(self) -> int: ...

class Volume:
    """A grid of values placed by an affine (voxel indices to metres); material where a
    value is at least iso."""

    def __init__(
        self, values: npt.ArrayLike, affine: npt.ArrayLike, iso: Optional[float] = None
    ) -> None:
        """values (nx, ny, nz) indexed [i, j, k]; affine 4×4 in metres; iso None: the
        midpoint of the finite values' range."""
    @staticmethod
    def from_nifti(path: _Path, iso: Optional[float] = None) -> Volume:
        """A NIfTI-1 file (.nii or .nii.gz), its affine as nibabel's, in metres."""
    @staticmethod
    def from_mesh(shape: Shape, voxel: float) -> Volume:
        """A closed solid voxelised with voxels of ``voxel`` metres (iso 0)."""
    def save(self, path: _Path) -> None:
        """NIfTI-1 float32 in metres (gzip for a name ending in .gz), written whole."""
    def shape(self, name: str = "volume") -> Shape:
        """The shape of the iso-surface, in the volume's frame."""
    def values(self) -> npt.NDArray[np.float32]:
        """A copy, (nx, ny, nz): values()[i, j, k] is voxel (i, j, k)."""
    @property
    def dims(self) -> Tuple[int, int, int]: ...
    @property
    def affine(self) -> npt.NDArray[np.float64]:
        """4×4, voxel indices to metres."""
    @property
    def iso(self) -> float: ...
    @property
    def centre(self) -> Tuple[float, float, float]: ...

class Cutter:
    """A tool cutting into a copy of a volume, each refresh a new version of its shape."""

    def __init__(self, volume: Volume, tool_radius: float, cut_force: float = 0.5) -> None: ...
    def press(self, centre: _Vec3, force: float, dt: float) -> int:
        """One tick of the tool at centre (m, volume frame) pressing with force N for dt
        s; the number of voxels removed."""
    def refresh(self) -> Optional[Shape]:
        """The next version of the shape, or None when nothing changed."""
    @property
    def shape(self) -> Shape: ...
    @property
    def volume(self) -> Volume: ...
    @property
    def removed(self) -> int: ...
    @property
    def tool_radius(self) -> float: ...
    @property
    def cut_force(self) -> float: ...

class Contact:
    """Where the proxy touches an object (world frame, metres)."""

    object: int
    triangle: int
    point: Tuple[float, float, float]
    normal: Tuple[float, float, float]
    shading_normal: Tuple[float, float, float]
    penetration: float
    constraints: int
    version: int

class Proxy:
    """The god-object proxy: the centre of the tool, a point or a sphere of tool_radius."""

    def __init__(
        self,
        position: _Vec3 = (0.0, 0.0, 0.0),
        max_force: float = DEFAULT_MAX_FORCE,
        skin: float = 1e-6,
        workspace_radius: float = 1000.0,
        tool_radius: float = 0.0,
    ) -> None: ...
    def tick(
        self, scene: Scene, hip: _Vec3, velocity: _Vec3 = (0.0, 0.0, 0.0)
    ) -> Tuple[Tuple[float, float, float], Tuple[float, float, float], Optional[Contact]]:
        """One tick: (force N, proxy position m, contact or None). Textures are felt;
        the scene's effects are rendered by haphe.run, not here."""
    def reset(self, position: _Vec3) -> None: ...
    @property
    def position(self) -> Tuple[float, float, float]: ...
    @property
    def tool_radius(self) -> float:
        """The radius of the tool, metres (0: a point)."""
