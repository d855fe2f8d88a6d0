"""What the overhead cameras report of a ball in the air (SSL-Vision's ground-ball model).

SSL-Vision finds the ball's colour blob in each camera image and turns it into field
coordinates assuming the ball lies on the ground: it intersects the camera ray through
the blob with the plane of a ground ball's centre (height = ball radius) and reports no
height (docs/references.md, "Vision and tracking"; ER-Force's tracker fits chips over
these rays for the same reason). A ball at height z therefore appears displaced away
from the point under the camera, by the factor

    (H - r) / (H - r - z)

on its offset from that point (H: camera height, r: ball radius, z: height of the
ball's lowest point): at 4 m, a ball 0.5 m up and 2 m from the camera's foot point
appears 0.27 m further out.

Layout (our model of a field of four cameras): the field is split into a 2 x 2 grid of
cells at its centre lines; one camera hangs :data:`CAMERA_HEIGHT_M` above the centre of
each cell (x = +-L/4, y = +-W/4) and sees the ball while the ball's ground position is
in its cell (no overlap, no hand-over). Frame and units: field frame, metres.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..physics.field import FieldGeometry
from ..physics.state import WorldState

#: m, height of every camera above the field
CAMERA_HEIGHT_M = 4.0


@dataclass(frozen=True)
class CameraRig:
    """Four cameras over a 2 x 2 grid of field cells (module docstring).

    Attributes:
        field: the field they cover.
        ball_radius: m; SSL-Vision's ground plane is at this height.
        height: camera height above the field (m).
    """

    field: FieldGeometry
    ball_radius: float
    height: float = CAMERA_HEIGHT_M

    def camera_over(self, pos: np.ndarray) -> np.ndarray:
        """(2,) foot point (m, field frame) of the camera that sees a ball at ground
        position ``pos``: the centre of the grid cell that holds it."""
        x, y = float(pos[0]), float(pos[1])
        return np.array((np.copysign(self.field.half_length / 2.0, x), np.copysign(self.field.half_width / 2.0, y)))

    def seen_position(self, pos: np.ndarray, z: float) -> np.ndarray:
        """(2,) reported position (m) of a ball at ground position ``pos`` whose lowest
        point is ``z`` m above the field: the ray from the camera through the ball's
        centre cut at the ground-ball plane. ``z`` = 0 returns ``pos`` unchanged."""
        if z <= 0.0:
            return np.asarray(pos, float)
        cam = self.camera_over(pos)
        scale = (self.height - self.ball_radius) / (self.height - self.ball_radius - z)
        return cam + (np.asarray(pos, float) - cam) * scale

    def observe(self, truth: WorldState) -> WorldState:
        """``truth`` as vision reports it: the ball at :meth:`seen_position`, height and
        vertical velocity 0 (SSL-Vision reports no height); the horizontal ball velocity
        stays the true one. A ball on the ground: ``truth`` itself."""
        if truth.ball_height <= 0.0 and truth.ball_vz == 0.0:
            return truth
        seen = self.seen_position(truth.ball_pos, truth.ball_height)
        seen.setflags(write=False)
        return replace(truth, ball_pos=seen, ball_height=0.0, ball_vz=0.0)
