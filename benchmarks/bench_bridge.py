"""Bridge benchmarks (loopback only): the server alone in lock-step 6v6 (simulated s per
wall s, one client sending empty requests of one control period; the served teams stand
still) and the command-to-effect delay in real-time mode (wall time from sending a
``RobotControl`` until the first vision frame that shows the robot moving; target: at
most one control period plus transport).

    PYTHONPATH=. python benchmarks/bench_bridge.py [--seconds 60] [--trials 40]

Writes results/bridge/bench_bridge.json. A benchmark, not a test: numbers depend on
the machine and its load (recorded).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from bench_bridge_common import provenance  # noqa: E402
from bridge_helpers import LOOP, loopback_server  # noqa: E402

from ssl_marl.bridge.lockstep import LockstepClient  # noqa: E402
from ssl_marl.bridge.proto import ssl_simulation_pb2 as sim_pb  # noqa: E402
from ssl_marl.bridge.proto import ssl_vision_wrapper_pb2 as wrap_pb  # noqa: E402
from ssl_marl.bridge.world import WorldConfig  # noqa: E402


def lockstep_speed(seconds: float) -> dict:
    server, vision, referee = loopback_server(WorldConfig(robots=6, seconds=seconds + 1), lockstep=True)
    thread = server.start()
    client = LockstepClient((LOOP, server.ports["sync_blue"]))
    dt = server.world.dt
    steps = int(round(seconds / dt))
    t0 = time.perf_counter()
    for _ in range(steps):
        client.step(dt)
        vision.receive()
        referee.receive()
    wall = time.perf_counter() - t0
    client.close()
    server.stop()
    thread.join(10)
    server.close()
    return {"robots": "6v6", "sim_s": seconds, "wall_s": round(wall, 3), "realtime_factor": round(seconds / wall, 2)}


def command_delay(trials: int) -> dict:
    import socket

    server, vision, referee = loopback_server(WorldConfig(robots=6, seconds=1e6, command_timeout_s=0.05))
    thread = server.start()
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    rng = np.random.default_rng(0)
    delays = []
    dt = server.world.dt
    for k in range(trials):
        time.sleep(0.3)  # robot at rest again
        start = None
        while start is None:  # the latest frame before the command: the rest position
            for data, _ in vision.receive():
                p = wrap_pb.SSL_WrapperPacket.FromString(data)
                if p.HasField("detection"):
                    r = next(r for r in p.detection.robots_blue if r.robot_id == 1)
                    start = (r.x, r.y)
            time.sleep(0.0005)
        time.sleep(rng.uniform(0, dt))  # random phase against the tick
        vision.receive()  # frames in between show the rest position too
        control = sim_pb.RobotControl()
        cmd = control.robot_commands.add(id=1)
        lv = cmd.move_command.local_velocity
        lv.forward, lv.left, lv.angular = (1.0 if k % 2 == 0 else -1.0), 0.0, 0.0
        t_send = time.perf_counter()
        sock.sendto(control.SerializeToString(), (LOOP, server.ports["blue"]))
        moved = False
        while not moved and time.perf_counter() - t_send < 1.0:
            for data, _ in vision.receive():
                p = wrap_pb.SSL_WrapperPacket.FromString(data)
                if not p.HasField("detection"):
                    continue
                r = next(r for r in p.detection.robots_blue if r.robot_id == 1)
                if abs(r.x - start[0]) + abs(r.y - start[1]) > 0.05:  # mm
                    delays.append(time.perf_counter() - t_send)
                    moved = True
                    break
            time.sleep(0.0002)
    server.stop()
    thread.join(10)
    server.close()
    sock.close()
    d = np.asarray(delays)
    return {"trials": trials, "measured": len(d), "control_period_s": dt,
            "delay_ms": {"median": round(float(np.median(d)) * 1e3, 2), "p95": round(float(np.percentile(d, 95)) * 1e3, 2),
                         "max": round(float(d.max()) * 1e3, 2)},
            "within_one_period": float(np.mean(d <= dt))}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=60.0, help="simulated s of the lock-step run")
    parser.add_argument("--trials", type=int, default=40, help="command-to-effect trials")
    parser.add_argument("--out", default="results/bridge/bench_bridge.json")
    args = parser.parse_args()
    result = {**provenance(), "lockstep_server_alone": lockstep_speed(args.seconds),
              "command_to_effect": command_delay(args.trials)}
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(result, indent=2) + "\n")
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
