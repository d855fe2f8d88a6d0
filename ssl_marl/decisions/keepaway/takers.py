"""Keepaway 3v2: the two hand-coded takers (:class:`TakerBehaviours`, mixed into
:class:`~ssl_marl.decisions.keepaway.env.KeepawayEnv`).

**Takers** (the standard hand-coded policy of the original 3v2: "with two takers both
go for the ball", ``KeepawayParams.takers = "press"``): the taker nearest to the ball
(0.2 m hysteresis) is the *chaser*: it goes to the ball with the go-to-ball skill at
full speed, around a keeper that shields the ball (to the ball's exposed side first,
see ``_chase_action``: the go-to-ball skill alone would push the keeper's back
forever). The other is the *presser*: it also goes for the ball; while a keeper holds
it (within 0.2 m), it goes round the keeper to the spot just beyond it on the far side
from the chaser (``keeper + press_m * unit(keeper - chaser)``, led by the ball's
velocity; from farther than 0.5 m it first runs at the keeper, since the spot turns
with the keeper too fast to chase round a wide circle), so a keeper that turns its back
to the chaser turns the ball into the presser; otherwise it runs the go-to-ball skill
like the chaser. With ``takers = "block"`` the second taker blocks the most dangerous
pass lane instead (of the keepers other than the one nearest the ball, the one whose lane
from the ball makes the largest angle with the chaser, 0.15 rad hysteresis; 40 % of the
way along it, at least 0.6 m from the ball, facing the ball); a shielding keeper can then
hold for the full 60 s (docs/RESULTS.md, "Keepaway 3v2").
"""

from __future__ import annotations

import math

import numpy as np

from ...physics.state import wrap_angle
from ...skills.motion import approach_speed, velocity_command
from ...skills.navigation import detour_waypoint


class TakerBehaviours:
    """Per-tick taker actions (``_taker_actions``) of
    :class:`~ssl_marl.decisions.keepaway.env.KeepawayEnv` (module docstring), from what
    yellow sees."""

    def _taker_actions(self) -> dict[str, np.ndarray]:
        seen = self.engine.vision_state("yellow")  # yellow's frame (rotated by pi)
        ball = seen.ball_pos
        tk = seen.yellow.pos
        d = np.sqrt(((tk - ball) ** 2).sum(axis=1))
        c = int(np.argmin(d))
        if d[self.chaser] <= d[c] + 0.2:
            c = self.chaser
        if c != self.chaser:
            self.taker_chase[c].reset()
        self.chaser = c
        o = 1 - c
        kp = seen.blue.pos
        held = self._holding_keeper(kp, ball)
        acts = {f"yellow_{c}": self._chase_action(seen, c, ball, tk[c], kp, held)}
        if self.params.takers == "press":
            acts[f"yellow_{o}"] = self._press_action(seen, o, ball, tk[o], kp, tk[c], held)
            return acts
        dk = np.sqrt(((kp - ball) ** 2).sum(axis=1))
        on_ball = int(np.argmin(dk)) if self.holder is None else self.holder
        cv = tk[c] - ball
        best, best_ang = None, -1.0
        angs = {}
        for k in range(3):
            if k == on_ball:
                continue
            lv = kp[k] - ball
            den = max(math.hypot(*lv) * math.hypot(*cv), 1e-9)
            angs[k] = math.acos(max(-1.0, min(1.0, float(lv @ cv) / den)))
            if angs[k] > best_ang:
                best, best_ang = k, angs[k]
        if self.block_target in angs and angs[self.block_target] >= best_ang - 0.15:
            best = self.block_target
        self.block_target = best
        lv = kp[best] - ball
        dl = math.hypot(*lv)
        along = min(max(self.params.block_fraction * dl, self.params.block_min_m), dl)
        target = ball + lv * (along / max(dl, 1e-9))
        name = f"yellow_{o}"
        if self.ticks % self.params.positioning_every == 0 or self._pos_cmd.get("blocker") != o:
            nav = self.taker_nav[o]
            nav.target = target
            nav.facing = math.atan2(ball[1] - tk[o][1], ball[0] - tk[o][0])
            self._pos_cmd[name] = nav.act(seen, o)
            self._pos_cmd["blocker"] = o
        acts[name] = self._pos_cmd[name]
        return acts

    @staticmethod
    def _holding_keeper(kp: np.ndarray, ball: np.ndarray) -> int | None:
        """The keeper nearest the ball if it is within 0.2 m of it (it holds / shields it)."""
        dk = np.sqrt(((kp - ball) ** 2).sum(axis=1))
        k = int(np.argmin(dk))
        return k if dk[k] <= 0.2 else None

    def _press_action(self, seen, o: int, ball: np.ndarray, me: np.ndarray, kp: np.ndarray,
                      chaser: np.ndarray, k: int | None) -> np.ndarray:
        """The presser (``takers = "press"``): while a keeper holds the ball (within 0.2 m),
        go round it to the point ``press_m`` beyond it on the far side from the chaser,
        ``keeper + press_m * unit(keeper - chaser)`` (led by the ball's velocity): a keeper
        that turns its back to the chaser turns the ball into the presser. Within 6 cm of
        that point, and whenever no keeper holds the ball, go to the ball with the
        go-to-ball skill. ``k``: the holding keeper (:meth:`_holding_keeper`) or None."""
        if k is None:
            return self.taker_chase[o].act(seen, o)
        u = kp[k] - chaser
        u = u / max(math.hypot(u[0], u[1]), 1e-9)
        spot = kp[k] + self.params.press_m * u
        dist = math.hypot(*(spot - me))
        if dist <= 0.06:
            return self.taker_chase[o].act(seen, o)
        lead = np.asarray(seen.ball_vel, float) * min(dist / self.rp.max_speed, 0.6)
        away = me - kp[k]
        r = math.hypot(away[0], away[1])
        if r > 0.5:
            # far: run at the keeper itself (the spot turns with the keeper at up to 2 rad/s,
            # too fast to chase round a wide circle), to the 0.3 m ring on this side
            spot = kp[k] + 0.3 * away / r
        return self._go_round(seen, o, ball, me, kp[k] + lead, spot + lead)

    def _go_round(self, seen, i: int, ball: np.ndarray, me: np.ndarray, keeper: np.ndarray,
                  side: np.ndarray) -> np.ndarray:
        """Taker ``i`` at full speed to ``side`` (a point touching the ball), passing the
        keeper at ``keeper`` at 0.24 m, facing the ball, dribbler on."""
        to_side = side - me
        dist = math.hypot(to_side[0], to_side[1])
        way = detour_waypoint(me, side, keeper[None, :], 0.22, 0.02)
        way = side if way is None else way
        d = way - me
        nd = max(math.hypot(d[0], d[1]), 1e-9)
        speed = min(self.rp.max_speed, approach_speed(dist, self.rp, v_end=2.0))
        h = float(seen.yellow.heading[i])
        err = float(wrap_angle(math.atan2(ball[1] - me[1], ball[0] - me[0]) - h))
        omega = float(np.clip(6.0 * err, -self.rp.max_omega, self.rp.max_omega))
        return velocity_command(seen, i, d * (speed / nd), omega, self.rp, dribble=True)

    def _chase_action(self, seen, c: int, ball: np.ndarray, me: np.ndarray, kp: np.ndarray,
                      k: int | None) -> np.ndarray:
        """The chasing taker: go-to-ball, but around a keeper that shields the ball (a
        keeper within 0.2 m of the ball while the taker is on the keeper's side of it):
        first at full speed to the ball's exposed side, ``ball + 0.13 m * unit(ball -
        keeper)`` (there its face touches the ball), passing the keeper at 0.24 m, then
        go-to-ball. The go-to-ball skill alone would push the keeper's back forever, and
        the navigation's 0.25 m clearance would keep it orbiting. ``k``: the holding keeper
        (:meth:`_holding_keeper`) or None."""
        if k is not None:
            u = ball - kp[k]
            u = u / max(math.hypot(u[0], u[1]), 1e-9)
            side = ball + 0.13 * u
            to_side = side - me
            dist = math.hypot(to_side[0], to_side[1])
            if float((ball - me) @ u) > 0.0 and dist > 0.06:
                return self._go_round(seen, c, ball, me, kp[k], side)
        return self.taker_chase[c].act(seen, c)


__all__ = ["TakerBehaviours"]
