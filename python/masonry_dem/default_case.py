"""The default demo case: Ferris & Tin-Loi wall 1 (the same as examples/ferris-tinloi-wall1.toml).

Blocks 0.4 x 0.175 m in running bond, 6 courses, 2.0 m long, the lowest course starting with a half block,
thickness 1 m, density 1000 kg/m3, g = 10 m/s2, dry joints with friction 0.65 and associative flow
(dilatancy 0.65), penalty stiffnesses 1e10 N/m3; horizontal forces lambda * W_i, load control.
Reference collapse multiplier 0.6429 (see docs/references.md, section 2).
"""

from __future__ import annotations

from .case import Case, parse_case

__all__ = ["DEFAULT_CASE_TOML", "default_case"]

#: The demo case as a case file (TOML, format 1).
DEFAULT_CASE_TOML = """\
# Reference: collapse multiplier 0.6429 (associative, exact limit analysis of this discrete model);
# published 0.643 (Ferris & Tin-Loi, Int. J. Mech. Sci. 43, 2001, 209-224).
format = 1
title = "Ferris & Tin-Loi wall 1"

[geometry]
thickness = 1.0             # [m]
density = 1000.0            # [kg/m3]

[geometry.running_bond]
block_length = 0.4          # [m]
block_height = 0.175        # [m]
courses = 6
length = 2.0                # [m]
first_course = "half"       # odd courses H F F F F H, even courses F F F F F

[base]
kind = "fixed"

[joints]                    # dry joints
normal_stiffness = 1e10     # [N/m3], a penalty: the collapse load does not depend on it
shear_stiffness = 1e10      # [N/m3]
friction = 0.65
cohesion = 0.0
tensile_strength = 0.0
dilatancy = 0.65            # associative (= friction); 0.0 for the non-associative analysis (about 0.640)

[loads]
gravity = 10.0              # [m/s2]
live = "horizontal_weight"

[analysis]
method = "static"
control = "load"
steps = 200
"""


def default_case() -> Case:
    """The demo case (Ferris & Tin-Loi wall 1), checked like a case file named "demo"."""
    return parse_case(DEFAULT_CASE_TOML, source="demo")
