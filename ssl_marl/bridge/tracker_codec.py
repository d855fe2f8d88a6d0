"""Tracked world snapshots -> SSL tracker packets (``TrackerWrapperPacket``).

The tracker protocol is in metres, m/s and rad in the field frame, like our
:class:`~ssl_marl.physics.state.WorldState`; the ball's ``pos.z`` is the snapshot's
``ball_height`` (height of its lowest point, m; 0 on the ground) and ``vel.z`` its
``ball_vz`` (m/s, up positive).
"""

from __future__ import annotations

from ..physics.state import WorldState
from .proto import ssl_vision_tracked_pb2 as trk_pb

TEAM_COLOR = {"blue": trk_pb.TEAM_COLOR_BLUE, "yellow": trk_pb.TEAM_COLOR_YELLOW}


def tracker_packet(ws: WorldState, frame_number: int, timestamp: float, uuid: str,
                   source_name: str = "ssl_marl") -> trk_pb.TrackerWrapperPacket:
    """The tracker packet of a field-frame snapshot ``ws`` (``timestamp`` in s)."""
    if ws.frame != "field":
        raise ValueError(f"tracker_packet expects a field-frame snapshot, got frame={ws.frame!r}")
    packet = trk_pb.TrackerWrapperPacket(uuid=uuid, source_name=source_name)
    frame = packet.tracked_frame
    frame.frame_number = int(frame_number) & 0xFFFFFFFF
    frame.timestamp = float(timestamp)
    ball = frame.balls.add(visibility=1.0 if ws.ball_visible else 0.0)
    ball.pos.x, ball.pos.y, ball.pos.z = float(ws.ball_pos[0]), float(ws.ball_pos[1]), float(ws.ball_height)
    ball.vel.x, ball.vel.y, ball.vel.z = float(ws.ball_vel[0]), float(ws.ball_vel[1]), float(ws.ball_vz)
    for team in ("blue", "yellow"):
        ts = ws.team(team)
        for i in range(ts.n):
            r = frame.robots.add(orientation=float(ts.heading[i]), vel_angular=float(ts.omega[i]), visibility=1.0)
            r.robot_id.id, r.robot_id.team_color = i, TEAM_COLOR[team]
            r.pos.x, r.pos.y = float(ts.pos[i, 0]), float(ts.pos[i, 1])
            r.vel.x, r.vel.y = float(ts.vel[i, 0]), float(ts.vel[i, 1])
    return packet
