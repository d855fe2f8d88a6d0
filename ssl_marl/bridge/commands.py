"""The ``serve`` and ``play`` subcommands: ``serve.register(subparsers)`` adds the parser
(``set_defaults(handler=serve.run)``), ``serve.run(args) -> int`` runs it; the same for
``play``.

Every stream's address is an option; the defaults are SSL's (multicast groups for
vision, referee and tracker), so on a machine that must not send to a multicast group,
give loopback unicast addresses for every stream.
"""

from __future__ import annotations

import argparse
from types import SimpleNamespace

from .transport import REFEREE_DEFAULT, VISION_DEFAULT

REALISM = ("none", "realistic", "randomized")


def _require_protobuf() -> None:
    """SystemExit with the install hint when the protobuf runtime (the ``ssl`` extra) is missing."""
    try:
        import google.protobuf  # noqa: F401
    except ImportError:
        raise SystemExit('the SSL bridge needs the protobuf runtime: pip install -e ".[ssl]"') from None


def _register_serve(subparsers) -> argparse.ArgumentParser:
    from ..runners.controllers import TEAM_KINDS

    p = subparsers.add_parser("serve", help="serve a match world over SSL's network protocols",
                              description="Run a match world in real time (or --speed X, or lock-step) and speak "
                                          "SSL-Vision, the SSL simulation protocol, grSim commands, referee and "
                                          "tracker packets.")
    p.add_argument("--robots", type=int, default=6, help="robots per team (default 6)")
    p.add_argument("--field", default="div_b", choices=("div_a", "div_b"), help="field size (default div_b)")
    p.add_argument("--seconds", type=float, default=300.0,
                   help="match length in simulated s (with --format ssl: s of playing time on the match clock, "
                        "which stops at STOP; default 300)")
    p.add_argument("--format", choices=("plain", "ssl"), default="plain",
                   help="match format: plain (restarts at once) or ssl (SSL game control: STOP, kickoffs and "
                        "free kicks in the referee packets, fouls, two halves on a clock that stops at STOP; "
                        "default plain)")
    p.add_argument("--seed", type=int, default=0, help="env and fallback-team seed (default 0)")
    p.add_argument("--realism", default="none", choices=REALISM, help="vision noise/latency preset (default none)")
    p.add_argument("--cameras", type=int, default=1, choices=(1, 2, 4, 8), help="simulated cameras (default 1)")
    p.add_argument("--blue-team", default="idle", choices=TEAM_KINDS,
                   help="our team that drives blue robots no client commands (default idle: stand still)")
    p.add_argument("--yellow-team", default="idle", choices=TEAM_KINDS,
                   help="our team that drives yellow robots no client commands (default idle)")
    p.add_argument("--client-teams", default="blue,yellow",
                   help="colours clients may command, comma-separated (default blue,yellow)")
    p.add_argument("--command-timeout", type=float, default=0.1,
                   help="s of simulated time a robot executes its last command (default 0.1; 0 = forever)")
    p.add_argument("--speed", type=float, default=1.0, help="simulated s per wall s in real-time mode (default 1)")
    p.add_argument("--lockstep", action="store_true",
                   help="step only on SimulationSyncRequests (TCP, varint length-prefixed) on the sync ports")
    p.add_argument("--vision", action="append", metavar="HOST:PORT",
                   help=f"vision destination, repeatable (default {VISION_DEFAULT}, multicast)")
    p.add_argument("--referee", action="append", metavar="HOST:PORT",
                   help=f"referee destination, repeatable (default {REFEREE_DEFAULT}, multicast)")
    p.add_argument("--tracker", action="append", metavar="HOST:PORT",
                   help="tracker destination, repeatable (default none: no tracker packets; SSL's is 224.5.23.2:10010)")
    p.add_argument("--listen-host", default="0.0.0.0", help="address the command ports bind (default 0.0.0.0)")
    p.add_argument("--control-port", type=int, default=10300, help="simulator control port (default 10300)")
    p.add_argument("--blue-port", type=int, default=10301, help="blue robot control port (default 10301)")
    p.add_argument("--yellow-port", type=int, default=10302, help="yellow robot control port (default 10302)")
    p.add_argument("--grsim-port", type=int, default=20011, help="legacy grSim command port (default 20011)")
    p.add_argument("--grsim-status-ports", default="30011,30012",
                   help="ports the grSim robot status goes to, blue,yellow (default 30011,30012)")
    p.add_argument("--sync-blue-port", type=int, default=10310, help="lock-step TCP port for blue (default 10310)")
    p.add_argument("--sync-yellow-port", type=int, default=10311, help="lock-step TCP port for yellow (default 10311)")
    p.add_argument("--geometry-every", type=float, default=3.0, help="s between geometry packets (default 3)")
    p.add_argument("--log", metavar="PATH", help="write SSL's standard log file of the vision and referee packets")
    p.add_argument("--replay", metavar="LOG", help="send a recorded SSL log out of the vision and referee "
                                                    "addresses instead of simulating")
    p.add_argument("--replay-video", metavar="OUT", help="with --replay: render the log's vision to OUT "
                                                         "(.gif or .mp4) instead of sending it")
    p.add_argument("--max-wall-s", type=float, help="stop after this many wall-clock seconds")
    p.set_defaults(handler=_run_serve)
    return p


def _run_serve(args: argparse.Namespace) -> int:
    _require_protobuf()
    from .server import BridgeServer, ServerConfig
    from .ssl_log import LogWriter, replay
    from .transport import UdpSender
    from .world import WorldConfig

    vision = tuple(args.vision or (VISION_DEFAULT,))
    referee = tuple(args.referee or (REFEREE_DEFAULT,))
    if args.replay and args.replay_video:
        from .log_tools import log_to_video

        n = log_to_video(args.replay, args.replay_video, robots=args.robots, field=args.field)
        print(f"wrote {n} frames of {args.replay} to {args.replay_video}")
        return 0
    if args.replay:
        v, r = UdpSender(vision), UdpSender(referee)
        try:
            n = replay(args.replay, v, r, speed=args.speed)
        finally:
            v.close()
            r.close()
        print(f"replayed {n} messages from {args.replay}")
        return 0
    teams = tuple(t.strip() for t in args.client_teams.split(",") if t.strip())
    if not set(teams) <= {"blue", "yellow"}:
        raise SystemExit(f"--client-teams: expected blue and/or yellow, got {args.client_teams!r}")
    status = tuple(int(p) for p in args.grsim_status_ports.split(","))
    if len(status) != 2:
        raise SystemExit("--grsim-status-ports: expected BLUE,YELLOW")
    world = WorldConfig(robots=args.robots, field=args.field, seconds=args.seconds, seed=args.seed,
                        realism=args.realism, n_cameras=args.cameras, blue_team=args.blue_team,
                        yellow_team=args.yellow_team, command_timeout_s=args.command_timeout, client_teams=teams,
                        tracker=bool(args.tracker), format=args.format)
    config = ServerConfig(vision=vision, referee=referee, tracker=tuple(args.tracker or ()),
                          listen_host=args.listen_host, control_port=args.control_port, blue_port=args.blue_port,
                          yellow_port=args.yellow_port, grsim_port=args.grsim_port, grsim_status_ports=status,
                          lockstep=args.lockstep, sync_blue_port=args.sync_blue_port,
                          sync_yellow_port=args.sync_yellow_port, speed=args.speed,
                          geometry_every_s=args.geometry_every)
    server = BridgeServer(world, config, log=LogWriter(args.log) if args.log else None)
    print(f"serving: ports {server.ports}, vision -> {list(vision)}, referee -> {list(referee)}", flush=True)
    try:
        stats = server.run(max_wall_s=args.max_wall_s)
    except KeyboardInterrupt:
        stats = dict(server.stats)
    finally:
        server.close()
    print(f"score {server.world.env.score}; counters {stats}")
    return 0


def _register_play(subparsers) -> argparse.ArgumentParser:
    from ..runners.controllers import TEAM_KINDS

    p = subparsers.add_parser("play", help="play one of our teams as a client of an SSL simulator",
                              description="Read vision and referee, decide with one of our teams, send robot "
                                          "commands (SSL simulation protocol or grSim packets) for one colour.")
    p.add_argument("--team", default="blue", choices=("blue", "yellow"), help="our colour (default blue)")
    p.add_argument("--kind", default="baseline", choices=TEAM_KINDS, help="which team of ours (default baseline)")
    p.add_argument("--robots", type=int, default=6, help="robots per team (default 6)")
    p.add_argument("--field", default="div_b", choices=("div_a", "div_b"), help="field size (default div_b)")
    p.add_argument("--seed", type=int, default=0, help="controller seed (default 0)")
    p.add_argument("--skill", action="append", default=[], metavar="SKILL=SOURCE",
                   help="replace one skill of an STP team (e.g. go-to-ball=runs/gtb/actor.pt), repeatable")
    p.add_argument("--decision", help="carrier decision of a passing team: handcoded, learned or an actor path")
    p.add_argument("--vision", default=VISION_DEFAULT, metavar="HOST:PORT",
                   help=f"vision address to listen on (default {VISION_DEFAULT}, multicast)")
    p.add_argument("--referee", default=REFEREE_DEFAULT, metavar="HOST:PORT",
                   help=f"referee address to listen on (default {REFEREE_DEFAULT}, multicast)")
    p.add_argument("--simulator", metavar="HOST:PORT",
                   help="where commands go (default 127.0.0.1 on 10301 blue / 10302 yellow, grSim 20011)")
    p.add_argument("--protocol", default="simulation", choices=("simulation", "grsim"),
                   help="command protocol (default simulation)")
    p.add_argument("--lockstep", metavar="HOST:PORT",
                   help="play in lock-step through this SimulationSyncRequest TCP endpoint (serve --lockstep's port "
                        "for our colour) instead of UDP vision and commands")
    p.add_argument("--max-wall-s", type=float, help="stop after this many wall-clock seconds")
    p.set_defaults(handler=_run_play)
    return p


def _run_play(args: argparse.Namespace) -> int:
    _require_protobuf()
    from ..runners.controllers import parse_skill_source, team_skills
    from .client import ClientConfig, PlayBrain, PlayClient

    sources = dict(parse_skill_source(s) for s in args.skill)
    skills = team_skills(args.kind, sources) if sources else None
    brain = PlayBrain(args.team, args.kind, args.robots, args.field, seed=args.seed, skills=skills,
                      decision=args.decision)
    if args.lockstep:
        from .client import run_lockstep_match

        steps = run_lockstep_match({args.team: args.lockstep}, {args.team: brain})
        print(f"played {steps} lock-step periods over {brain.decisions} frames")
        return 0
    client = PlayClient(brain, ClientConfig(vision=args.vision, referee=args.referee, simulator=args.simulator,
                                            protocol=args.protocol))
    print(f"playing {args.team} ({args.kind}) -> {client.simulator} by {args.protocol}", flush=True)
    try:
        sent = client.run(max_wall_s=args.max_wall_s)
    except KeyboardInterrupt:
        sent = client.sent
    finally:
        client.close()
    print(f"sent {sent} command packets over {brain.decisions} frames")
    return 0


#: ``serve.register(subparsers)`` / ``serve.run(args)``
serve = SimpleNamespace(register=_register_serve, run=_run_serve)
#: ``play.register(subparsers)`` / ``play.run(args)``
play = SimpleNamespace(register=_register_play, run=_run_play)
