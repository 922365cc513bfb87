"""haphe: haptic rendering against triangle meshes.

Shapes from mesh files or numpy arrays, with batch queries (inside/outside, watertight
first crossings of segments, nearest surface points) that take and give numpy arrays and
run without the GIL; scenes of placed shapes; the god-object proxy ticked against them;
the servo loop with a device; and volumes (NIfTI-1 files, numpy grids, voxelised
shapes) rendered by their iso-surface and cut by a tool.

Units are SI (metres, newtons, seconds); triangles are counter-clockwise seen from
outside. Triangle indices are always the face indices of the mesh as given; the arrays of
``Shape.arrays`` and ``Scene.deform`` are in the surface's own order instead.
"""

from ._haphe import (
    DEFAULT_MAX_FORCE,
    Contact,
    Cutter,
    DeviceError,
    HapheError,
    Proxy,
    Scene,
    Shape,
    Volume,
    __version__,
    allocations,
    check_deforming,
    run,
    validate,
)

__all__ = [
    "DEFAULT_MAX_FORCE",
    "Contact",
    "Cutter",
    "DeviceError",
    "HapheError",
    "Proxy",
    "Scene",
    "Shape",
    "Volume",
    "__version__",
    "allocations",
    "check_deforming",
    "run",
    "validate",
]
