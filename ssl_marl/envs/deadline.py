"""The real-time control deadline: one small object for both places that need it.

SSL software sends one command per control period (``period_s`` = 1/60 s here, the
paper's section 4.2). Two questions are asked of that period, and both are answered
by :class:`ControlDeadline`:

* *Did this command's computation fit in the period?* (:meth:`ControlDeadline.met`,
  :meth:`ControlDeadline.command`). The runners (matches, tactic evaluation) time
  each team's ``act`` and, when it took longer than one period, drop the new
  command and keep executing the previous one; the drop is counted in
  :attr:`ControlDeadline.missed`. Each team holds its own object, as if both teams
  ran on their own computers. The simulation is not paced by the wall clock.
* *How many control ticks has the wall clock advanced since the last command?*
  (:meth:`ControlDeadline.wait_for_tick`). The env in real-time mode
  (``EnvConfig.realtime``) sleeps until the next tick; a command that arrives late
  misses the ticks in between (the robots keep the previous command for them).

Both depend on machine load, so only step mode (no deadline) is reproducible.
It lives in ``envs`` (not ``runners``) because the env itself uses it and data
flows physics -> envs -> skills -> plays -> runners.
"""

from __future__ import annotations

import math
import time
from typing import Callable, TypeVar

T = TypeVar("T")


class ControlDeadline:
    """A control period (s) and the count of commands that missed it.

    Args:
        period_s: the control period (s), e.g. ``EnvConfig.dt`` = 1/60 s.
        clock: a monotonic clock in seconds (default :func:`time.perf_counter`;
            tests pass a fake one).
        sleep: how to wait (default :func:`time.sleep`).
    """

    def __init__(self, period_s: float, clock: Callable[[], float] = time.perf_counter,
                 sleep: Callable[[float], None] = time.sleep) -> None:
        if not (isinstance(period_s, (int, float)) and math.isfinite(period_s) and period_s > 0):
            raise ValueError(f"ControlDeadline: period_s must be a positive number of seconds, got {period_s!r}")
        self.period_s = float(period_s)
        self.clock = clock
        self.sleep = sleep
        self.missed = 0
        self._next_tick = 0.0

    # ------------------------------------------------------ compute budget
    def met(self, elapsed_s: float) -> bool:
        """True if a computation that took ``elapsed_s`` (s) fits in one period;
        otherwise counts one miss and returns False."""
        if elapsed_s > self.period_s:
            self.missed += 1
            return False
        return True

    def command(self, compute: Callable[[], T], previous: T) -> tuple[T, float]:
        """Run ``compute()``, timed. Returns (the new command, or ``previous`` when
        the computation missed the deadline; elapsed wall time in s)."""
        t0 = self.clock()
        new = compute()
        elapsed = self.clock() - t0
        return (new if self.met(elapsed) else previous), elapsed

    # --------------------------------------------------------- tick pacing
    def start(self) -> None:
        """Start the tick clock: the first tick is one period from now."""
        self._next_tick = self.clock() + self.period_s

    def wait_for_tick(self) -> int:
        """Sleep until the next tick; return how many ticks elapsed (1 = on time,
        k > 1 = the command arrived k - 1 ticks late; those are added to
        :attr:`missed`)."""
        now = self.clock()
        if now <= self._next_tick:
            self.sleep(self._next_tick - now)
            self._next_tick += self.period_s
            return 1
        late = int((now - self._next_tick) // self.period_s) + 1
        self._next_tick += (late + 1) * self.period_s
        self.missed += late
        return late + 1
