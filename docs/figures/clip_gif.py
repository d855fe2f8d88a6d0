"""Cut a time window out of an animated GIF (e.g. the seconds around a goal).

    python docs/figures/clip_gif.py IN.gif OUT.gif --start 11 --end 21 [--every 1]

Frame times come from the GIF's own frame durations (identical frames merged by the
writer keep their summed duration), so ``--start``/``--end`` are simulated seconds
when the GIF was written by ``ssl-marl match --render`` (which runs at a fixed
frames-per-simulated-second). ``--every N`` keeps one frame in N (smaller file).
"""

from __future__ import annotations

import argparse

import numpy as np
from PIL import Image

from ssl_marl.envs.animation import write_animation


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("src", help="input GIF")
    p.add_argument("dst", help="output GIF")
    p.add_argument("--start", type=float, required=True, help="window start (s)")
    p.add_argument("--end", type=float, required=True, help="window end (s)")
    p.add_argument("--every", type=int, default=1, help="keep one frame in N (default 1)")
    a = p.parse_args(argv)
    frames, t, fps = [], 0.0, None
    with Image.open(a.src) as im:
        for k in range(im.n_frames):
            im.seek(k)
            dur = im.info.get("duration", 100) / 1000.0
            fps = fps or 1.0 / dur
            n = max(1, int(round(dur * fps)))  # merged identical frames count n times
            rgb = np.asarray(im.convert("RGB"))
            for _ in range(n):
                if a.start <= t < a.end:
                    frames.append(rgb)
                t += 1.0 / fps
    kept = frames[:: a.every]
    write_animation(kept, a.dst, fps=max(1, int(round(fps / a.every))))
    print(f"{len(kept)} frames ({a.start}-{a.end} s of {t:.1f} s) -> {a.dst}")


if __name__ == "__main__":
    main()
