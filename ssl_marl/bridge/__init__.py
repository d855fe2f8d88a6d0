"""Speak SSL: the network bridge between the simulator and SSL team software / tools.

* :mod:`.server`: :class:`~.server.BridgeServer`, a match world served over SSL's
  protocols (vision, tracker and referee out; simulation-protocol and grSim commands,
  simulator control in; lock-step over TCP: :mod:`.lockstep`).
* :mod:`.client`: :class:`~.client.PlayClient`, one of our teams as a client of any
  SSL simulator.
* Codecs, one job each: :mod:`.vision_codec` (world <-> SSL-Vision packets),
  :mod:`.command_codec` (robot commands <-> normalised actions),
  :mod:`.referee_codec`, :mod:`.tracker_codec`; framing: :mod:`.wire`; sockets:
  :mod:`.transport`; SSL log files: :mod:`.ssl_log`.
* :mod:`.commands`: the ``serve`` and ``play`` subcommands.

The schema (``proto/*.proto``, package ``ssl_marl.bridge``) is wire-compatible with
the SSL messages (docs/references.md, "SSL network protocols"); the generated modules
need the ``ssl`` extra (``pip install -e ".[ssl]"``, the protobuf runtime).
"""
