"""Round trip through the SSL bridge on loopback: serve a 3v3 match in lock-step mode,
command blue robot 1 by the SSL simulation protocol, read the SSL-Vision detections
back, teleport the ball into a goal and watch the referee count it.

    PYTHONPATH=. python examples/bridge_round_trip.py

Every stream goes to 127.0.0.1 (ephemeral ports): nothing is sent to a multicast group.
"""

from __future__ import annotations

from ssl_marl.bridge.lockstep import LockstepClient
from ssl_marl.bridge.proto import ssl_referee_pb2 as ref_pb
from ssl_marl.bridge.proto import ssl_simulation_pb2 as sim_pb
from ssl_marl.bridge.server import BridgeServer, ServerConfig
from ssl_marl.bridge.transport import UdpReceiver
from ssl_marl.bridge.world import WorldConfig

LOOP = "127.0.0.1"


def main(argv: list[str] | None = None) -> dict:
    """Run the round trip; returns what it saw (robot position mm, score, the step error)."""
    vision, referee = UdpReceiver((LOOP, 0)), UdpReceiver((LOOP, 0))
    config = ServerConfig(vision=(f"{LOOP}:{vision.port}",), referee=(f"{LOOP}:{referee.port}",), listen_host=LOOP,
                          control_port=0, blue_port=0, yellow_port=0, grsim_port=0, grsim_status_ports=(9, 9),
                          sync_blue_port=0, sync_yellow_port=0, lockstep=True)
    server = BridgeServer(WorldConfig(robots=3, seconds=10.0, yellow_team="baseline"), config)
    thread = server.start()
    client = LockstepClient((LOOP, server.ports["sync_blue"]))
    dt = server.world.dt

    control = sim_pb.RobotControl()
    move = control.robot_commands.add(id=1).move_command.local_velocity
    move.forward, move.left, move.angular = 1.0, 0.0, 0.0  # m/s forward
    for k in range(30):
        resp = client.step(dt, control)
    robot = next(r for r in resp.detection[-1].robots_blue if r.robot_id == 1)
    print(f"after 0.5 s at 1 m/s: blue 1 at ({robot.x:.0f}, {robot.y:.0f}) mm, "
          f"dribbler contact {resp.robot_control_response.feedback[1].dribbler_ball_contact}")

    goal = sim_pb.SimulatorCommand()
    ball = goal.control.teleport_ball
    ball.x, ball.y, ball.vx, ball.vy = 4.4, 0.35, 2.0, 0.0  # m, m/s: past yellow's keeper into its goal
    for _ in range(30):
        client.step(dt, simulator_command=goal if _ == 0 else None)
    scores = [ref_pb.Referee.FromString(d) for d, _ in referee.receive()]
    last = scores[-1]
    print(f"referee: {ref_pb.Referee.Command.Name(last.command)}, blue {last.blue.score} - {last.yellow.score} yellow")

    bad = client.step(0.01)
    error = bad.robot_control_response.errors[0].code
    print(f"sim_step 0.01 s: {error}")
    client.close()
    server.stop()
    thread.join()
    server.close()
    vision.close()
    referee.close()
    return {"robot_mm": (robot.x, robot.y), "score": (last.blue.score, last.yellow.score),
            "command": ref_pb.Referee.Command.Name(last.command), "step_error": error}


if __name__ == "__main__":
    main()
