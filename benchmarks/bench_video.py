"""GIF writing: the streaming VideoSink vs Pillow's whole-list save (write_animation).

    python benchmarks/bench_video.py

Renders a 10 s 6v6 Division B episode with random (non-kicking) actions, seed 0, 480 px,
every 6th control step (10 frames per simulated second), then writes the same frames
with ``ssl_marl.envs.animation.write_animation`` (all frames in memory, Pillow
``save_all``) and with ``ssl_marl.runners.video.VideoSink`` (one frame at a time), and
prints file sizes, write times and the mean absolute error of the decoded frames
against the rendered ones (0-255 scale). Peak memory is measured separately with
``/usr/bin/time -v`` (docs/BENCHMARKS.md, "Video memory").
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
os.environ.setdefault("SDL_VIDEODRIVER", "dummy")


def main() -> None:
    import imageio.v3 as iio

    from ssl_marl.envs import parallel_env
    from ssl_marl.envs.animation import write_animation
    from ssl_marl.runners.video import VideoSink

    env = parallel_env(n_blue=6, n_yellow=6, render_mode="rgb_array", render_width_px=480, max_time_s=10)
    env.reset(seed=0)
    frames = [env.render()]
    rng = np.random.default_rng(0)
    no_kick = np.array([1, 1, 1, 0, 0], np.float32)
    k = 0
    while env.agents:
        env.step({a: rng.uniform(-1, 1, 5).astype(np.float32) * no_kick for a in env.agents})
        k += 1
        if k % 6 == 0:
            frames.append(env.render())
    ref = np.stack(frames).astype(int)
    with tempfile.TemporaryDirectory() as d:
        pillow, sink = Path(d) / "pillow.gif", Path(d) / "sink.gif"
        t0 = time.perf_counter()
        write_animation(frames, pillow, fps=10)
        t_pillow = time.perf_counter() - t0
        t0 = time.perf_counter()
        with VideoSink(sink, 10) as s:
            for f in frames:
                s.add(f)
        t_sink = time.perf_counter() - t0
        for name, path, t in (("write_animation", pillow, t_pillow), ("VideoSink", sink, t_sink)):
            back = iio.imread(path, index=None)[..., :3].astype(int)
            err = float(np.abs(back - ref).mean()) if back.shape == ref.shape else float("nan")
            print(f"{name:16s} frames {len(frames)}  size {path.stat().st_size / 1e3:.0f} kB  "
                  f"write {t:.2f} s  mean abs error {err:.2e}")


if __name__ == "__main__":
    main()
