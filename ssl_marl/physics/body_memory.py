"""Direct numpy views of Box2D bodies' state, bypassing one SWIG call per field.

pybox2d exposes every body field through SWIG: reading a body's position, angle,
velocity and angular velocity costs ~2.5 us (each ``b2Vec2`` read builds a Python
proxy object), writing a velocity ~0.3 us. With 23 bodies and 2 sub-steps that is
most of an 11v11 step. The C++ ``b2Body`` of Box2D 2.3 is a plain struct (no
virtual table) whose first fields are, in float32 slots of 4 bytes::

    0 m_type, 1 m_flags, 2 m_islandIndex,
    3-4 m_xf.p (position), 5-6 m_xf.q (sin, cos),
    7-8 m_sweep.localCenter, 9-10 m_sweep.c0, 11-12 m_sweep.c, 13 m_sweep.a0,
    14 m_sweep.a (angle), 15 m_sweep.alpha0,
    16-17 m_linearVelocity, 18 m_angularVelocity

:func:`layout_ok` checks this layout against the SWIG getters once per process
(on a throw-away world); where it does not hold, callers fall back to SWIG.
Bodies of one world created one after another lie at a fixed stride in Box2D's
block allocator, so one strided view covers them all (:func:`bodies_view`; None
if they do not). The views point into memory owned by the ``b2World``: keep the
world alive as long as the view (the callers rebuild the view with every world).

Writing the velocity slots is what ``b2Body::SetLinearVelocity`` /
``SetAngularVelocity`` do for a dynamic body that is awake; our worlds are built
with ``doSleep=False`` and only dynamic bodies are written, so the two agree.
Units are Box2D's (see :data:`ssl_marl.physics.world.SCALE`).
"""

from __future__ import annotations

import ctypes
import functools

import Box2D
import numpy as np

POS = slice(3, 5)
ANGLE = 14
VEL = slice(16, 18)
OMEGA = 18
VEL_OMEGA = slice(16, 19)
_SLOTS = 48  # float32 slots viewed per body (sizeof(b2Body) is 192 bytes in 2.3.10)


def address(body) -> int:
    """Address of a body's C++ ``b2Body`` (bytes)."""
    return int(body.this)


def _address(body) -> int:
    return int(body.this)


@functools.lru_cache(maxsize=1)
def layout_ok() -> bool:
    """True if the float slots above hold what the SWIG getters return (checked once)."""
    try:
        w = Box2D.b2World(gravity=(0.0, 0.0), doSleep=False)
        bodies = []
        for k in range(3):
            b = w.CreateDynamicBody(position=(1.5 + k, -2.25 * k), angle=0.3 + k, linearVelocity=(0.7, -1.1 * k),
                                    angularVelocity=2.5 - k)
            b.CreateCircleFixture(radius=0.5, density=1.0)
            bodies.append(b)
        w.Step(0.01, 8, 3)
        view = bodies_view(bodies, check=False)
        if view is None:
            return False
        for b, row in zip(bodies, view):
            p, v = b.position, b.linearVelocity
            if (float(row[3]), float(row[4]), float(row[ANGLE]), float(row[16]), float(row[17]), float(row[OMEGA])) != \
                    (p[0], p[1], b.angle, v[0], v[1], b.angularVelocity):
                return False
        view[1, VEL] = (4.0, 5.0)
        view[1, OMEGA] = -3.0
        if tuple(bodies[1].linearVelocity) != (4.0, 5.0) or bodies[1].angularVelocity != -3.0:
            return False
        mem, slot = span_view(np.array([address(b) for b in bodies]))
        mem[slot[2] + OMEGA] = 1.25
        return bool(bodies[2].angularVelocity == 1.25 and mem[slot[0] + ANGLE] == np.float32(bodies[0].angle))
    except Exception:  # any surprise (other Box2D build): use SWIG
        return False


class _Span:
    """Minimal ``__array_interface__`` provider: n_floats float32 starting at address base."""

    def __init__(self, base: int, n_floats: int) -> None:
        self.__array_interface__ = {"shape": (n_floats,), "typestr": "<f4", "data": (base, False), "version": 3}


def span_view(addresses: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """One flat float32 view covering every body at ``addresses`` (bytes, any shape),
    and the index of each body's first slot in it.

    The view spans the whole address range, including memory that belongs to other
    objects or is not mapped: only ever index it at ``slot0 + [0, 48)`` of live bodies.
    """
    a = np.asarray(addresses, dtype=np.int64)
    base = int(a.min()) & ~15
    n_floats = (int(a.max()) - base) // 4 + _SLOTS
    view = np.asarray(_Span(base, n_floats))
    return view, (a - base) // 4


def bodies_view(bodies: list, check: bool = True) -> np.ndarray | None:
    """(len(bodies), 48) float32 strided view over consecutive bodies, or None if the
    bodies are not at one fixed stride (or the layout check fails)."""
    if check and not layout_ok():
        return None
    addr = [_address(b) for b in bodies]
    if not addr:
        return None
    stride = addr[1] - addr[0] if len(addr) > 1 else _SLOTS * 4
    if stride < _SLOTS * 4 or any(a - addr[0] != i * stride for i, a in enumerate(addr)):
        return None
    nbytes = stride * (len(addr) - 1) + _SLOTS * 4
    buf = (ctypes.c_char * nbytes).from_address(addr[0])
    return np.ndarray((len(addr), _SLOTS), np.float32, buffer=buf, strides=(stride, 4))
