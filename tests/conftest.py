import os

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")

try:  # keep the suite on one thread per process: CI has 2 cores
    import torch

    torch.set_num_threads(1)
except ImportError:  # pragma: no cover
    pass
