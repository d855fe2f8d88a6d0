"""World snapshots <-> SSL-Vision packets.

Frames: SSL-Vision reports positions in millimetres in the field frame (origin at the
centre, +x towards the goal blue attacks in our field frame, headings in rad CCW from
+x); our snapshots (:class:`~ssl_marl.physics.state.WorldState`) are in metres in the
same field frame. Velocities are not part of a detection: a receiver differentiates.
A ball's ``z`` is the height of its lowest point (mm; 0 on the ground) as the snapshot
has it: a snapshot of the env's realistic cameras (:mod:`ssl_marl.envs.camera`) reports
a ball in the air projected onto the ground plane with height 0, as SSL-Vision's single
cameras do; a snapshot without realism reports the true height, as simulators that
fill ``z`` do.

Cameras: the field is cut into ``n_cameras`` (1, 2, 4 or 8) equal rectangles
(:func:`camera_regions`); each camera reports the objects inside its rectangle grown
by ``overlap_m``, so objects near a seam are seen twice, as with real SSL-Vision.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..physics.field import FieldGeometry
from ..physics.params import BallParams, RobotParams
from ..physics.state import TeamState, WorldState, make_team_state
from .proto import ssl_vision_detection_pb2 as det_pb
from .proto import ssl_vision_geometry_pb2 as geo_pb
from .proto import ssl_vision_wrapper_pb2 as wrap_pb

CAMERA_GRIDS = {1: (1, 1), 2: (2, 1), 4: (2, 2), 8: (4, 2)}
ROBOT_HEIGHT_MM = 150.0
PIXELS_PER_MM = 0.25  # pixel coordinates are the camera-local position at this scale


@dataclass(frozen=True)
class CameraRegion:
    """One camera's field-frame rectangle (m), overlap included."""

    camera_id: int
    x_min: float
    x_max: float
    y_min: float
    y_max: float

    def sees(self, xy: np.ndarray) -> np.ndarray:
        """Boolean mask of the (n, 2) field-frame points (m) inside the rectangle."""
        xy = np.asarray(xy, float).reshape(-1, 2)
        return ((xy[:, 0] >= self.x_min) & (xy[:, 0] <= self.x_max)
                & (xy[:, 1] >= self.y_min) & (xy[:, 1] <= self.y_max))

    def pixel(self, x_m: float, y_m: float) -> tuple[float, float]:
        """Pixel coordinates of a field point: mm from the rectangle's corner x scale."""
        return (x_m - self.x_min) * 1000.0 * PIXELS_PER_MM, (self.y_max - y_m) * 1000.0 * PIXELS_PER_MM


def camera_regions(field: FieldGeometry, n_cameras: int, overlap_m: float = 0.3) -> list[CameraRegion]:
    """The camera rectangles covering the field and its boundary (ids from 0, row-major
    from -x, -y). ValueError for a camera count other than 1, 2, 4 or 8."""
    if n_cameras not in CAMERA_GRIDS:
        raise ValueError(f"n_cameras must be one of {tuple(CAMERA_GRIDS)}, got {n_cameras!r}")
    nx, ny = CAMERA_GRIDS[n_cameras]
    hx = field.half_length + field.boundary_width
    hy = field.half_width + field.boundary_width
    xs = np.linspace(-hx, hx, nx + 1)
    ys = np.linspace(-hy, hy, ny + 1)
    regions = []
    for j in range(ny):
        for i in range(nx):
            regions.append(CameraRegion(len(regions),
                                        xs[i] - (overlap_m if i > 0 else 1.0), xs[i + 1] + (overlap_m if i < nx - 1 else 1.0),
                                        ys[j] - (overlap_m if j > 0 else 1.0), ys[j + 1] + (overlap_m if j < ny - 1 else 1.0)))
    return regions


def _add_robots(repeated, team: TeamState, mask: np.ndarray, region: CameraRegion) -> None:
    for i in np.flatnonzero(mask):
        x, y = float(team.pos[i, 0]), float(team.pos[i, 1])
        px, py = region.pixel(x, y)
        repeated.add(confidence=1.0, robot_id=int(i), x=x * 1000.0, y=y * 1000.0,
                     orientation=float(team.heading[i]), pixel_x=px, pixel_y=py, height=ROBOT_HEIGHT_MM)


def detection_frames(ws: WorldState, regions: list[CameraRegion], frame_numbers: list[int], t_capture: float,
                     t_sent: float) -> list[det_pb.SSL_DetectionFrame]:
    """One detection frame per camera from a field-frame snapshot ``ws`` (a hidden
    ball, ``ws.ball_visible`` False, is left out; the ball's ``z`` is
    ``ws.ball_height``). Times in seconds (Unix-based when a game controller listens);
    ``frame_numbers[k]`` is camera k's frame counter."""
    if ws.frame != "field":
        raise ValueError(f"detection_frames expects a field-frame snapshot, got frame={ws.frame!r}")
    frames = []
    for region in regions:
        f = det_pb.SSL_DetectionFrame(frame_number=int(frame_numbers[region.camera_id]) & 0xFFFFFFFF,
                                      t_capture=float(t_capture), t_sent=float(t_sent),
                                      camera_id=region.camera_id, t_capture_camera=float(t_capture))
        if ws.ball_visible and region.sees(ws.ball_pos)[0]:
            bx, by = float(ws.ball_pos[0]), float(ws.ball_pos[1])
            px, py = region.pixel(bx, by)
            f.balls.add(confidence=1.0, area=80, x=bx * 1000.0, y=by * 1000.0, z=float(ws.ball_height) * 1000.0,
                        pixel_x=px, pixel_y=py)
        _add_robots(f.robots_yellow, ws.yellow, region.sees(ws.yellow.pos), region)
        _add_robots(f.robots_blue, ws.blue, region.sees(ws.blue.pos), region)
        frames.append(f)
    return frames


def _mm(v: float) -> int:
    return int(round(v * 1000.0))


def geometry_data(field: FieldGeometry, robot: RobotParams, ball: BallParams,
                  line_thickness_m: float = 0.01) -> geo_pb.SSL_GeometryData:
    """The field's SSL-Vision geometry (mm): sizes, the named lines and the centre circle."""
    L2, W2, t = field.half_length, field.half_width, line_thickness_m
    size = geo_pb.SSL_GeometryFieldSize(
        field_length=_mm(field.length), field_width=_mm(field.width), goal_width=_mm(field.goal_width),
        goal_depth=_mm(field.goal_depth), boundary_width=_mm(field.boundary_width),
        penalty_area_depth=_mm(field.defense_depth), penalty_area_width=_mm(field.defense_width),
        center_circle_radius=_mm(field.center_circle_radius), line_thickness=_mm(t),
        goal_center_to_penalty_mark=_mm(field.penalty_mark_distance), goal_height=155,
        ball_radius=ball.radius * 1000.0, max_robot_radius=robot.radius * 1000.0)
    d, w2 = field.defense_depth, field.defense_width / 2
    lines = [
        ("TopTouchLine", (-L2, W2), (L2, W2), geo_pb.TopTouchLine),
        ("BottomTouchLine", (-L2, -W2), (L2, -W2), geo_pb.BottomTouchLine),
        ("LeftGoalLine", (-L2, -W2), (-L2, W2), geo_pb.LeftGoalLine),
        ("RightGoalLine", (L2, -W2), (L2, W2), geo_pb.RightGoalLine),
        ("HalfwayLine", (0.0, -W2), (0.0, W2), geo_pb.HalfwayLine),
        ("CenterLine", (-L2, 0.0), (L2, 0.0), geo_pb.CenterLine),
        ("LeftPenaltyStretch", (-L2 + d, -w2), (-L2 + d, w2), geo_pb.LeftPenaltyStretch),
        ("RightPenaltyStretch", (L2 - d, -w2), (L2 - d, w2), geo_pb.RightPenaltyStretch),
        ("LeftFieldLeftPenaltyStretch", (-L2, -w2), (-L2 + d, -w2), geo_pb.LeftFieldLeftPenaltyStretch),
        ("LeftFieldRightPenaltyStretch", (-L2, w2), (-L2 + d, w2), geo_pb.LeftFieldRightPenaltyStretch),
        ("RightFieldLeftPenaltyStretch", (L2, w2), (L2 - d, w2), geo_pb.RightFieldLeftPenaltyStretch),
        ("RightFieldRightPenaltyStretch", (L2, -w2), (L2 - d, -w2), geo_pb.RightFieldRightPenaltyStretch),
    ]
    for name, p1, p2, kind in lines:
        size.field_lines.add(name=name, p1=geo_pb.Vector2f(x=p1[0] * 1000.0, y=p1[1] * 1000.0),
                             p2=geo_pb.Vector2f(x=p2[0] * 1000.0, y=p2[1] * 1000.0), thickness=t * 1000.0, type=kind)
    size.field_arcs.add(name="CenterCircle", center=geo_pb.Vector2f(x=0.0, y=0.0),
                        radius=field.center_circle_radius * 1000.0, a1=0.0, a2=float(2 * np.pi),
                        thickness=t * 1000.0, type=geo_pb.CenterCircle)
    return geo_pb.SSL_GeometryData(field=size)


def wrapper(detection: det_pb.SSL_DetectionFrame | None = None,
            geometry: geo_pb.SSL_GeometryData | None = None) -> wrap_pb.SSL_WrapperPacket:
    """An SSL_WrapperPacket holding a detection frame and/or geometry."""
    packet = wrap_pb.SSL_WrapperPacket()
    if detection is not None:
        packet.detection.CopyFrom(detection)
    if geometry is not None:
        packet.geometry.CopyFrom(geometry)
    return packet


def field_from_geometry(geometry: geo_pb.SSL_GeometryData, name: str = "from_vision") -> FieldGeometry:
    """A :class:`FieldGeometry` (m) from received SSL-Vision geometry (mm)."""
    f = geometry.field
    kw = dict(name=name, length=f.field_length / 1000.0, width=f.field_width / 1000.0,
              goal_width=f.goal_width / 1000.0, goal_depth=f.goal_depth / 1000.0,
              boundary_width=f.boundary_width / 1000.0)
    if f.HasField("penalty_area_depth"):
        kw["defense_depth"] = f.penalty_area_depth / 1000.0
    if f.HasField("penalty_area_width"):
        kw["defense_width"] = f.penalty_area_width / 1000.0
    if f.HasField("center_circle_radius"):
        kw["center_circle_radius"] = f.center_circle_radius / 1000.0
    return FieldGeometry(**kw)


@dataclass
class Detections:
    """Detections of one capture time merged over cameras (field frame, m, rad):
    ``ball`` (2,) or None; ``blue`` / ``yellow``: {robot id: (x, y, heading)}."""

    t_capture: float
    ball: np.ndarray | None
    blue: dict[int, tuple[float, float, float]]
    yellow: dict[int, tuple[float, float, float]]


def merge_frames(frames: list[det_pb.SSL_DetectionFrame]) -> Detections:
    """Merge camera frames of one capture time: an object seen by several cameras is
    averaged (headings by their unit vectors); the ball is the most confident one's
    camera average. Non-finite coordinates are dropped."""
    balls: list[tuple[float, float]] = []
    robots: dict[str, dict[int, list[tuple[float, float, float]]]] = {"blue": {}, "yellow": {}}
    t = max((f.t_capture for f in frames), default=0.0)
    for f in frames:
        for b in f.balls:
            if np.isfinite(b.x) and np.isfinite(b.y):
                balls.append((b.x / 1000.0, b.y / 1000.0))
        for team, rep in (("blue", f.robots_blue), ("yellow", f.robots_yellow)):
            for r in rep:
                if np.isfinite(r.x) and np.isfinite(r.y) and np.isfinite(r.orientation):
                    robots[team].setdefault(int(r.robot_id), []).append((r.x / 1000.0, r.y / 1000.0, r.orientation))
    merged = {}
    for team, by_id in robots.items():
        merged[team] = {}
        for rid, obs in by_id.items():
            a = np.asarray(obs)
            h = float(np.arctan2(np.sin(a[:, 2]).mean(), np.cos(a[:, 2]).mean()))
            merged[team][rid] = (float(a[:, 0].mean()), float(a[:, 1].mean()), h)
    ball = np.asarray(balls).mean(axis=0) if balls else None
    return Detections(float(t), ball, merged["blue"], merged["yellow"])


def empty_team(n: int) -> TeamState:
    """n robots at the origin, at rest (placeholders until vision sees them)."""
    return make_team_state(np.zeros((n, 2)), np.zeros(n), np.zeros((n, 2)), np.zeros(n), np.zeros(n, bool),
                           np.ones(n, bool))
