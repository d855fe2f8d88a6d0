"""The skill catalog: one module per skill, each registering one
:class:`~ssl_marl.skills.registry.SkillDef`.

To add a skill: write ``catalog/<name>.py`` (build the record, ``register`` it) and
add ``"<name>"`` to :data:`MODULES`. Nothing else dispatches on skill names.
"""

from __future__ import annotations

import importlib

#: catalog modules, in registry order (the order of CLI choices and tables)
MODULES = ("go_to_ball", "aim_to_shoot", "pass_ball", "receive", "redirect", "chip_pass", "drive_forward", "move_to_point")

for _name in MODULES:
    importlib.import_module(f"{__name__}.{_name}")
