"""SSL log files of our matches: record a match in-process (:func:`record_match_log`,
what ``ssl-marl match`` can call to write SSL's standard log) and render a recorded
log's vision to a GIF / MP4 (:func:`log_to_video`). Playing a log back out of the
vision and referee ports is :func:`ssl_marl.bridge.ssl_log.replay` (``serve --replay``).
"""

from __future__ import annotations

import os
from typing import Any

from .ssl_log import MESSAGE_TYPES, LogWriter, read_log


def record_match_log(path: str | os.PathLike, blue: str = "baseline", yellow: str = "baseline", robots: int = 6,
                     field: str = "div_b", seconds: float = 300.0, seed: int = 0, realism: str = "none",
                     n_cameras: int = 1, time_origin: float = 0.0, format: str = "plain") -> dict[str, int]:
    """Play a match of our teams ``blue`` / ``yellow`` in-process (the bridge's world,
    so the seeded start and referee are :func:`ssl_marl.runners.match.play_match`'s, and
    its env has chip kicks exactly when ``play_match``'s has: when a team chips) and
    write every vision frame (each camera, each control period; geometry every 3 s) and
    referee packet to an SSL log at ``path``; returns the score. Timestamps:
    ``time_origin`` + simulated time (ns). ``format``: "plain" or "ssl" (the match format,
    as ``ssl-marl match --format``; the referee packets carry SSL's game control)."""
    from ..runners.controllers import CHIP_KINDS
    from .vision_codec import wrapper
    from .world import BridgeWorld, WorldConfig

    world = BridgeWorld(WorldConfig(robots=robots, field=field, seconds=seconds, seed=seed, realism=realism,
                                    n_cameras=n_cameras, blue_team=blue, yellow_team=yellow,
                                    chip_kicks=blue in CHIP_KINDS or yellow in CHIP_KINDS, format=format))
    last_geometry = -float("inf")
    with LogWriter(path) as log:
        changed = True
        while True:
            t = time_origin + world.t
            ns = int(round(t * 1e9))
            if world.t - last_geometry >= 3.0 - 1e-9:
                log.write_vision(ns, wrapper(geometry=world.geometry).SerializeToString())
                last_geometry = world.t
            for frame in world.detections(t, t):
                log.write_vision(ns, wrapper(detection=frame).SerializeToString())
            if changed or world.stats["steps"] % 6 == 0:
                log.write_referee(ns, world.referee.message(int(round(t * 1e6))).SerializeToString())
            if world.finished:
                break
            _, changed = world.step(int(round((time_origin + world.t + world.dt) * 1e6)))
    return dict(world.env.score)


def log_to_video(log_path: str | os.PathLike, out_path: str | os.PathLike, robots: int = 6, field: Any = "div_b",
                 fps: float = 30.0, width_px: int = 640) -> int:
    """Render a log's detections (cameras merged per capture time) to ``out_path``
    (.gif or .mp4) at ``fps`` frames per logged second; returns the frames written."""
    from ..envs.animation import VideoSink
    from ..envs.render import FieldRenderer
    from ..physics.field import FieldGeometry
    from ..physics.params import BallParams, RobotParams
    from .perception import VisionWorld
    from .proto import ssl_referee_pb2 as ref_pb
    from .proto import ssl_vision_wrapper_pb2 as wrap_pb
    from .vision_codec import merge_frames

    geom, robot, ball = FieldGeometry.from_name(field), RobotParams(), BallParams()
    vision = VisionWorld(robots, geom, robot, ball)
    renderer = FieldRenderer(geom, robot, ball, width_px=width_px)
    sink = VideoSink(out_path, fps)
    pending: dict[float, list] = {}
    next_t, written, score = None, 0, "0 - 0"
    ok = False

    def flush(upto: float | None) -> None:
        nonlocal next_t, written
        for t in sorted(k for k in pending if upto is None or k < upto):
            state = vision.update(merge_frames(pending.pop(t)))
            if state is None:
                continue
            if next_t is None or t >= next_t - 1e-9:
                sink.add(renderer.draw(state, info_text=f"t={state.t:5.1f} s   blue {score} yellow"))
                written += 1
                next_t = t + 1.0 / fps

    try:
        for msg in read_log(log_path):
            if msg.message_type == MESSAGE_TYPES["referee_2013"]:
                ref = ref_pb.Referee.FromString(msg.payload)
                score = f"{ref.blue.score} - {ref.yellow.score}"
            elif msg.message_type == MESSAGE_TYPES["vision_2014"]:
                packet = wrap_pb.SSL_WrapperPacket.FromString(msg.payload)
                if packet.HasField("detection"):
                    t = packet.detection.t_capture
                    flush(t)
                    pending.setdefault(t, []).append(packet.detection)
        flush(None)
        ok = True
    finally:
        sink.close(ok)
        renderer.close()
    return written
