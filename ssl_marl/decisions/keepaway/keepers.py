"""Keepaway 3v2: what the keepers do between decisions (:class:`KeeperBehaviours`, mixed
into :class:`~ssl_marl.decisions.keepaway.env.KeepawayEnv`): the options in progress
(hold, and a pass's Pass / Receive tactics) and the fixed behaviours.

**Hold** (option 0): the keeper faces and drifts (``hold_speed``, 0.5 m/s) away from
the nearest taker, bent towards the square's centre near a side (turning at most
``hold_turn_rate``, the turn rate changed gently so the dribbler keeps the ball), so
its body stays between the taker and the ball.

**Fixed behaviours** (no decisions): while the ball is loose (nobody controls it and
no pass is under way) the keeper nearest to it (0.2 m hysteresis) fetches it with
the go-to-ball skill (approach speed governor 0.8 m/s at contact, as the tactics);
every other keeper not passing or receiving *gets open*: it moves (facing the ball)
to the point of a 5 x 5 grid 0.6 m inside the square that maximises
``min(distance to the nearest taker, 2 m) + 1.5 * min(pass-lane angle at the ball
to the takers, pi/4) - penalties`` (within 1.2 m of the ball: -2; within 1.5 m of
another keeper's spot: -2), re-planned every 0.2 s, keepers in index order.
"""

from __future__ import annotations

import math

import numpy as np

from ...physics.state import wrap_angle
from ...plays.pass_tactic import PassState
from ...plays.receive_tactic import ReceiveState
from ...plays.shoot import govern_approach
from ...skills.motion import velocity_command
from .params import HOLD


class KeeperBehaviours:
    """Per-tick keeper actions of :class:`~ssl_marl.decisions.keepaway.env.KeepawayEnv`
    (module docstring); ``tick_actions`` adds the takers' (``_taker_actions``)."""

    def tick_actions(self) -> dict[str, np.ndarray]:
        seen = self.engine.vision_state("blue")
        acts: dict[str, np.ndarray] = {}
        busy = set()
        i = self.holder
        if i is not None:
            busy.add(i)
            if self.option == HOLD:
                acts[f"blue_{i}"] = self._hold_action(seen, i)
            else:
                r = self.receiver
                busy.add(r)
                rt = self.receive_tactics[r]
                if not self.kicked:
                    pt = self.pass_tactics[i]
                    pt.set_params(receiver_ready=rt.state is ReceiveState.READY)
                    acts[f"blue_{i}"] = pt.act(seen, i)
                    if pt.state is PassState.DONE:
                        busy.discard(i)
                else:
                    busy.discard(i)
                acts[f"blue_{r}"] = rt.act(seen, r)
        else:
            c = self.controller()
            if c is not None:  # about to decide (or deciding): keep the ball
                busy.add(c)
                acts[f"blue_{c}"] = self._hold_action(seen, c)
            else:
                f = self._pick_fetcher(seen)
                busy.add(f)
                a = self.keeper_fetch[f].act(seen, f)
                acts[f"blue_{f}"] = govern_approach(a, seen, f, self.rp, self.bp, self.params.fetch_touch_speed,
                                                    3.0)
        free = [k for k in range(3) if k not in busy]
        if free:
            self._spot_age += 1
            if self._spot_age >= self._replan_ticks:
                self._plan_spots(seen, free)
                self._spot_age = 0
            fresh = self.ticks % self.params.positioning_every == 0
            for k in free:
                name = f"blue_{k}"
                if fresh or name not in self._pos_cmd:
                    nav = self.keeper_nav[k]
                    nav.target = self.spots[k]
                    d = seen.ball_pos - seen.blue.pos[k]
                    nav.facing = math.atan2(d[1], d[0])
                    self._pos_cmd[name] = nav.act(seen, k)
                acts[name] = self._pos_cmd[name]
        self._pos_cmd = {k: v for k, v in self._pos_cmd.items() if k in acts or not k.startswith("blue")}
        acts.update(self._taker_actions())
        return acts

    def _hold_action(self, seen, i: int) -> np.ndarray:
        """Shield the ball (module docstring): face and drift along
        ``unit(away from the nearest taker) + w * unit(to the centre)``, ``w`` growing
        from 0 at 1.2 m from the nearest side to 1.5 on it, so a keeper near a side
        is not pushed out of the square."""
        p = self.params
        pos, h = seen.blue.pos[i], float(seen.blue.heading[i])
        tk = seen.yellow.pos
        dists = np.sqrt(((tk - pos) ** 2).sum(axis=1))
        away = pos - tk[int(np.argmin(dists))]
        na = math.hypot(away[0], away[1])
        away = away / na if na > 1e-6 else np.array([1.0, 0.0])
        nc = math.hypot(pos[0], pos[1])
        to_c = -pos / nc if nc > 1e-6 else np.zeros(2)
        edge = self._half - max(abs(float(pos[0])), abs(float(pos[1])))
        wc = 1.5 * min(max((1.2 - edge) / 1.2, 0.0), 1.0)
        d = away + wc * to_c
        nd = math.hypot(d[0], d[1])
        d = d / nd if nd > 1e-6 else np.array([math.cos(h), math.sin(h)])
        err = float(wrap_angle(math.atan2(d[1], d[0]) - h))
        omega = float(np.clip(6.0 * err, -p.hold_turn_rate, p.hold_turn_rate))
        w0 = float(seen.blue.omega[i])  # change the turn rate gently: the face would shed the ball
        omega = w0 + float(np.clip(omega - w0, -p.hold_alpha * self.dt, p.hold_alpha * self.dt))
        v = d * p.hold_speed
        v0 = seen.blue.vel[i]  # gentle acceleration: the dribbler holds the ball up to 5 m/s^2
        dv = v - v0
        ndv = math.hypot(dv[0], dv[1])
        lim = 2.5 * self.dt
        if ndv > lim:
            v = v0 + dv * (lim / ndv)
        return velocity_command(seen, i, v, omega, self.rp, dribble=True)

    def _pick_fetcher(self, seen) -> int:
        d = np.sqrt(((seen.blue.pos - seen.ball_pos) ** 2).sum(axis=1))
        f = int(np.argmin(d))
        if self.fetcher is not None and d[self.fetcher] <= d[f] + 0.2:
            f = self.fetcher
        if f != self.fetcher:
            self.keeper_fetch[f].reset()
        self.fetcher = f
        return f

    def _plan_spots(self, seen, free: list[int]) -> None:
        """Get-open spots for the free keepers (module docstring)."""
        g = self._grid
        ball = seen.ball_pos
        tk = seen.yellow.pos
        dt = np.sqrt(((g[:, None, :] - tk[None, :, :]) ** 2).sum(axis=2))  # (P, 2)
        score = np.minimum(dt.min(axis=1), 2.0)
        lane = g - ball
        dl = np.sqrt((lane ** 2).sum(axis=1))
        tv = tk - ball
        dtb = np.sqrt((tv ** 2).sum(axis=1))
        cosang = (lane @ tv.T) / np.maximum(dl[:, None] * dtb[None, :], 1e-9)
        ang = np.arccos(np.clip(cosang, -1.0, 1.0))
        ang = np.where(dtb[None, :] <= dl[:, None] + 0.3, ang, math.pi)
        score = score + 1.5 * np.minimum(ang.min(axis=1), math.pi / 4)
        score = score - 2.0 * (dl < 1.2)
        taken = [seen.blue.pos[k] for k in range(3) if k not in free]
        for k in free:
            s = score.copy()
            for q in taken:
                s -= 2.0 * (np.sqrt(((g - q) ** 2).sum(axis=1)) < 1.5)
            j = int(np.argmax(s))
            self.spots[k] = g[j]
            taken.append(g[j])


__all__ = ["KeeperBehaviours"]
