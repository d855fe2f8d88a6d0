"""Box2D units and solver settings shared by the single and the batched worlds.

Box2D runs in decimetres (``SCALE`` Box2D units per metre): the 43 mm ball is then a
comfortable size for the solver and Box2D's restitution velocity threshold (1 unit/s)
becomes 0.1 m/s (:mod:`ssl_marl.physics.world`).
"""

SCALE = 10.0  #: Box2D units per metre
VEL_ITERS = 8  #: Box2D velocity iterations per step
POS_ITERS = 3  #: Box2D position iterations per step

#: m: each physics sub-step the ball's distance to a face must be at least this far
#: "inside" to count as touching (the polygon skin and solver slop are ~1 mm).
_FACE_PENETRATION_TOL = 0.01

#: Box2D collision categories and masks: the ball in flight above the robots collides with walls only.
CAT_WALL, CAT_ROBOT, CAT_BALL = 0x0001, 0x0002, 0x0004
MASK_ALL, MASK_WALLS = 0xFFFF, CAT_WALL
