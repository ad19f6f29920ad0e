"""Type stubs of the compiled core (Rust, PyO3). SI units throughout: m, N, Pa, kg, s.

Block indices: wall blocks are numbered 0..n_wall-1 in the order given; the base (if any) and
the top beam (if any) come after them (see `Model.base_index`, `Model.top_index`).
Interface families: "bed", "head", "base", "top".
An argument left out (None) takes the core's default: the Rust `Default` of the options it belongs
to, documented in docs/case-format.md under the matching key.
"""

from typing import Any, Callable, Dict, Literal, Optional, Sequence, Tuple, TypedDict, Union

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]

__version__: str
JOINT_LAW_KEYS: list[str]  # the keys of a joint-law dict (and of [joints] tables)
MAX_FOLLOW_STEPS: int  # the largest follow_steps of Model.solve_limit
DEFAULTS: dict[str, object]  # the core's defaults of Model's and the solvers' arguments that Python shows
DEFAULTS_3D: dict[str, object]  # the core's defaults of Model3D's arguments that Python shows

from .errors import ConvergenceError as ConvergenceError
from .errors import InputError as InputError
from .errors import MasonryError as MasonryError
from .errors import MechanismError as MechanismError

def running_bond(
    block_length: float,
    block_height: float,
    courses: Optional[int] = None,
    length: Optional[float] = None,
    first_course: Optional[Literal["half", "full"]] = None,
    openings: Optional[Sequence[Sequence[float]]] = None,
    *,
    height: Optional[float] = None,
) -> FloatArray:
    """Blocks [x0, y0, x1, y1] (shape (n, 4), m) of a running-bond wall standing at y = 0 from x = 0.

    block_length, block_height: a whole block's size [m]; length: the wall's length [m] (required).
    Exactly one of courses (whole courses) and height (the wall's height [m]): with height, the whole
    courses that fit and, if more is left, a last course cut to the remainder; a remainder under 25%
    of block_height is refused, the message naming the nearest heights and block heights that fit.
    Courses alternate between starting with a half block ("half") and a whole block ("full");
    a block that would cross x = length is cut there. Openings [x0, y0, x1, y1] (in m) are cut out:
    a block partly inside one is cut at its edges into the parts outside it (straight jambs, sill
    and lintel; exactly the opening's area removed), an edge within 5% of a block's size of a joint
    being moved onto the joint so that no sliver of a block is made."""

def pattern(block_length: float, block_height: float, rows: Sequence[Sequence[float]]) -> FloatArray:
    """Blocks [x0, y0, x1, y1] (shape (n, 4), m) from courses listed bottom to top; each entry is a
    length in units of block_length, a negative entry is a gap of that length."""

class _ArchGeometry(TypedDict):
    blocks: list[list[list[float]]]
    supports: list[list[list[float]]]
    intrados: list[list[float]]
    extrados: list[list[float]]
    carried: list[tuple[int, list[float], float]]

def arch(
    kind: Literal["semicircular", "segmental", "pointed", "elliptical"],
    thickness: float,
    voussoirs: int,
    span: Optional[float] = None,
    radius: Optional[float] = None,
    rise: Optional[float] = None,
    abutment_width: Optional[float] = None,
    abutment_height: Optional[float] = None,
    pier_width: Optional[float] = None,
    pier_height: Optional[float] = None,
    pier_courses: Optional[int] = None,
    backfill_level: Optional[float] = None,
    backfill_density: Optional[float] = None,
    wall_thickness: Optional[float] = None,
    gravity: Optional[float] = None,
) -> _ArchGeometry:
    """An arch of voussoirs, as a dict: "blocks" (the voussoirs left to right, then the piers' blocks, each a list of
    vertices [x, y] counter-clockwise, m), "supports" (the two abutments, left and right; empty on piers), "intrados"
    and "extrados" (the joints' ends along each, left to right, m). Model(blocks, supports=supports) is the arch.

    kind: "semicircular", "segmental", "pointed" or "elliptical". The intrados springs from y = 0, symmetric about
    x = 0. span: the intrados's clear span [m], or radius: the centreline's radius [m] (semicircular and segmental
    only). rise: the intrados's rise [m] (segmental: less than its radius; pointed: at least span / 2; elliptical:
    the vertical semi-axis). thickness: the ring's, along the joints [m]; voussoirs: their number (even for a pointed
    arch: a joint at its crown).
    Joints: radial on circular arcs (a pointed arch's crown joint vertical), normal to the intrados of an elliptical
    arch (at equal steps of its parametric angle, the extrados the intrados offset by the thickness); the intrados and
    extrados of each voussoir are straight chords between its joints' ends.
    Springings: abutments (fixed supports; the default) out to abutment_width [m] from the intrados's springing point
    (default: the springing joint's extent) and abutment_height [m] below it (default: the thickness); or piers of
    wall blocks, pier_width [m] wide from the intrados's springing point and pier_height [m] from the ground to it,
    in pier_courses courses (default 1: a single block), standing on the base.
    Backfill: backfill_level [m] (its top, above the springing line y = 0) and backfill_density [kg/m3], both or
    neither: each voussoir carries the fill in the vertical strip over its extrados chord up to the level, its weight
    (density x wall_thickness x gravity x the strip's area) at the extrados under the strip's centroid, in "carried"
    (a list of (block, [x, y], weight [N]), empty without a fill: Model(..., carried=made["carried"])). wall_thickness
    [m] and gravity [m/s2] are the Model's own (defaults those of Model: 1.0 and 9.81), so that the fill's mass is its
    density times its volume. The fill's weight and mass move with the voussoir under it; its lateral pressure, its
    strength and the fill over the abutments or piers are not modelled."""

def gable(
    block_length: float,
    block_height: float,
    length: float,
    eaves_height: float,
    ridge_height: float,
    ridge_x: Optional[float] = None,
    first_course: Optional[Literal["half", "full"]] = None,
) -> list[list[list[float]]]:
    """The blocks of a gable wall, each a list of vertices [x, y] counter-clockwise (m), course by course bottom to top,
    left to right: a running bond (block_length x block_height [m], courses alternating half-block and whole-block
    starts, first_course "half" or "full" for the lowest) from x = 0 to length [m] on y = 0, under a top that rises in
    a straight line from eaves_height [m] at x = 0 to ridge_height [m] at x = ridge_x [m] (default: length / 2) and
    falls to eaves_height at x = length; a ridge at 0 or length makes a single slope. The blocks are cut at the rakes
    (convex polygons); a cut block of less than 25% of a whole block's area is merged with its neighbour towards the
    ridge, and a course at the ridge lower than 25% of block_height is joined to the course below: nothing is
    dropped, the blocks tile the gable. Model(blocks) is the wall."""

def stone_wall(
    length: float,
    height: float,
    stone_length: float,
    stone_height: float,
    irregularity: float = 0.3,
    head_angle: float = 15.0,
    bed_angle: float = 0.0,
    seed: int = 0,
) -> list[list[list[float]]]:
    """The stones of a stone wall, each a list of vertices [x, y] counter-clockwise (m), course by course bottom to top,
    left to right: a wall from x = 0 to length [m] and from y = 0 to height [m] (a flat base and a flat top), in
    round(height / stone_height) courses of heights drawn in stone_height (1 +- irregularity) [m], of stones of lengths
    drawn in stone_length (1 +- irregularity) [m] (irregularity in 0..=0.5). Head joints are inclined from the vertical
    by angles drawn within +-head_angle (degrees, 0..=30), bed joints from the horizontal within +-bed_angle (degrees,
    0..=10; less where a course would be left thinner than half its height at the wall's ends); no stone is shorter than
    25% of stone_length along a bed joint, and the head joints of two courses are at least that far apart along the bed
    joint between them. Every joint is an edge the two stones share. The same seed (an integer in 0..2^64) gives the
    same wall, bit for bit, on any machine. Model(stones) is the wall."""

class _Vaulted(TypedDict):
    polyhedra: list[list[list[float]]]
    supports: list[list[list[float]]]

def barrel_vault(
    kind: Literal["semicircular", "segmental", "pointed", "elliptical"],
    thickness: float,
    voussoirs: int,
    length: float,
    block_length: Optional[float] = None,
    span: Optional[float] = None,
    radius: Optional[float] = None,
    rise: Optional[float] = None,
    abutment_width: Optional[float] = None,
    abutment_height: Optional[float] = None,
    pier_width: Optional[float] = None,
    pier_height: Optional[float] = None,
    pier_courses: Optional[int] = None,
) -> _Vaulted:
    """A barrel vault, as a dict: "polyhedra" (its blocks, each a list of vertices [x, y, z], m) and "supports" (the two
    abutments; empty on walls). Model3D(polyhedra=..., supports=..., base=False) is the vault on abutments,
    Model3D(polyhedra=...) the vault on walls (they stand on the base).

    Its cross-section is arch()'s (kind, thickness, voussoirs, span, radius, rise, abutment_width, abutment_height,
    pier_width, pier_height, pier_courses: the same meaning, the same defaults) in the plane (x, z), z up, the
    springing line z = 0; the piers become walls along the axis. The axis is y, from 0 to length [m]. block_length [m]:
    each course (a voussoir, or a course of a wall, extruded) is cut into blocks this long along the axis, every other
    course starting with a half block (the joints staggered by half a block; no piece shorter than 5% of a block);
    left out: the arch extruded one block deep, each course a single block."""

def cross_vault(
    kind: Literal["semicircular", "pointed"],
    thickness: float,
    voussoirs: int,
    span: Optional[float] = None,
    radius: Optional[float] = None,
    rise: Optional[float] = None,
    abutment_width: Optional[float] = None,
    abutment_height: Optional[float] = None,
    pier_width: Optional[float] = None,
    pier_height: Optional[float] = None,
    pier_courses: Optional[int] = None,
) -> _Vaulted:
    """A cross (groin) vault, as a dict: "polyhedra" (its voussoirs, then the piers' blocks if on piers, each a list of
    vertices [x, y, z], m) and "supports" (four fixed blocks under the corners; empty on piers).
    Model3D(polyhedra=..., supports=..., base=False) is the vault on its corner supports, Model3D(polyhedra=...) the
    vault on piers (they stand on the base).

    Two barrels of one section cross at right angles over a square bay: arch()'s (kind "semicircular" or "pointed",
    thickness, voussoirs, span, radius, rise, abutment_width, abutment_height, pier_width, pier_height, pier_courses:
    the same meaning, the same defaults) in the plane (x, z), springing at z = 0, along y, and the same along x. The
    bay is |x|, |y| <= a, a the extrados's half span at the springing. Each barrel is kept where its tunnel is the
    higher (|x| <= |y| for the one along y): each voussoir of each of the four webs is one block from the bay's side
    to the groins, the diagonal vertical planes x = y and x = -y. The blocks: the web over y > 0 (the arch's voussoirs
    left to right), then the same web turned by 90, 180 and 270 degrees about z. The arch's right abutment, or its
    right pier's courses, stand under each corner as squares in plan (|x| and |y| from the intrados's half span out
    to its width): four fixed supports, or four piers of free blocks on the base listed after the vault's blocks,
    corner by corner (+x +y, -x +y, -x -y, +x -y), each bottom to top."""

def dome(
    kind: Literal["hemispherical", "pointed"],
    thickness: float,
    meridians: int,
    parallels: int,
    span: Optional[float] = None,
    radius: Optional[float] = None,
    rise: Optional[float] = None,
) -> _Vaulted:
    """A dome, as a dict: "polyhedra" (its voussoirs ring by ring from the springing up, each a list of vertices
    [x, y, z], m) and "supports" (empty: it stands on the base). Model3D(polyhedra=...) is the dome on the base.

    kind: "hemispherical" (give radius, the middle surface's [m], or span, the intrados's diameter [m]) or "pointed"
    (span and rise, the intrados's, rise >= span / 2). Its meridian is the right half of arch()'s of 2 parallels
    voussoirs (radial joints) revolved about the z axis, the springing at z = 0; thickness [m] along the joints;
    meridians (3 at least): the voussoirs of each ring, at equal angles; parallels: the rings. Each voussoir is the
    convex hull of its corners (planar faces: chords of the intrados and extrados), the crown's ring of wedges
    meeting on the axis; the meridian joints run through every ring."""

def running_bond_3d(
    length: float,
    height: float,
    thickness: float,
    block_length: float,
    block_height: float,
    first_course: Optional[Union[Literal["half", "full"], float]] = None,
    openings: Optional[Sequence[Sequence[float]]] = None,
) -> FloatArray:
    """Boxes [x0, y0, z0, x1, y1, z1] (shape (n, 6), m) of a single leaf in running bond: along x from x = 0 to
    length, y from 0 to thickness, z from 0 to height [m], of blocks block_length x thickness x block_height [m].

    first_course: how the lowest course starts at x = 0: "half" (the default: with a half block), "full" (with a
    whole block) or an offset [m] in [0, block_length) by which its joints are shifted to the left; each course above
    is shifted by half a block more. A height that is not a whole number of courses gets a last course cut to fit
    (one under 25% of block_height is refused, as in running_bond). A joint that would fall closer than 5% of a block
    to a course's end is left out (the end block is longer by as much). openings: [x0, z0, x1, z1] (m), holes through
    the leaf, cut as cut_openings_3d cuts them."""

def buttressed_wall(
    length: float,
    height: float,
    thickness: float,
    block_length: float,
    block_height: float,
    spacing: float,
    buttress_width: float,
    buttress_depth: float,
    bonded: bool = True,
) -> FloatArray:
    """Boxes [x0, y0, z0, x1, y1, z1] (shape (n, 6), m) of a wall with buttresses: the wall along x (x in [0, length], y in
    [0, thickness]), height high, in running bond of blocks block_length x thickness x block_height (the lowest course
    starting with a whole block at x = 0, the next with a half), and buttresses against its face y = 0, each a column
    of one block per course, buttress_width along x by buttress_depth (y in [-buttress_depth, 0]) [m], their axes at
    x = spacing (k + 1/2) for each k whose buttress ends 5% of a block short of the wall's end at least. bonded (the
    default): in the lowest course and every other one above it the buttress's block runs through the wall (to y =
    thickness) and the wall's course stops against it; not bonded: the buttresses stand against the wall's face.
    spacing must exceed buttress_width by 10% of a block. The blocks course by course from the bottom, the wall's
    along +x, then the buttresses'."""

def u_wall(
    facade: float,
    height: float,
    returns: float,
    thickness: float,
    block_length: float,
    block_height: float,
    openings: Optional[Sequence[Sequence[float]]] = None,
) -> FloatArray:
    """Boxes [x0, y0, z0, x1, y1, z1] (shape (n, 6), m) of a U of three walls one block thick: a facade along x (x in
    [0, facade], y in [0, thickness]) and two return walls along +y at its ends, returns long from the facade's outer
    face, height high [m]; blocks block_length x thickness x block_height [m].

    The corners are bonded: in the even courses the facade's end blocks run over the corners, in the odd ones the
    returns' do; within each wall the courses are in running bond. block_length must exceed thickness by 5% of a
    block. openings: [x0, z0, x1, z1] (m), holes through the facade, clear of the corners (cut_openings_3d)."""

def corner_wall(
    facade: float,
    height: float,
    returns: float,
    thickness: float,
    block_length: float,
    block_height: float,
    openings: Optional[Sequence[Sequence[float]]] = None,
) -> FloatArray:
    """Boxes [x0, y0, z0, x1, y1, z1] (shape (n, 6), m) of an L of two walls one block thick: a facade along x (x in
    [0, facade], y in [0, thickness]) and one return wall along +y at x = 0, returns long from the facade's outer
    face, height high [m], the corner bonded as in u_wall; the facade's far end is free. openings: [x0, z0, x1, z1]
    (m), holes through the facade, clear of the corner (cut_openings_3d)."""

def cut_openings_3d(boxes: npt.ArrayLike, openings: Sequence[Sequence[float]]) -> FloatArray:
    """`boxes` [x0, y0, z0, x1, y1, z1] (m) with `openings` [x0, z0, x1, z1] (m) cut through the facade (the blocks of
    the smallest y) over its depth: a block partly inside an opening becomes its parts outside it (straight jambs,
    sill and lintel), no part thinner than 5% of the block being made; an opening that reaches a block deeper than
    the facade (a return wall's block over a corner) is refused."""

def convex_hulls(blocks: Sequence[npt.ArrayLike], key: str = "polyhedra") -> list[tuple[FloatArray, list[list[int]]]]:
    """The convex hull of each block's vertices: a list of (vertices (k, 3) [m], faces, each a list of indices into
    them counter-clockwise seen from outside), as Model3D makes its polyhedra (the contact tolerance of the box around
    every vertex given). blocks: a list of vertex lists (each a (k, 3) array or a list of [x, y, z] rows [m]); key:
    the name of the list in the refusals, which name the block (`polyhedra[3]: fewer than 4 vertices off one plane:
    it has no volume ...`, `polyhedra[0]: vertex 2 (...): coordinate NaN is not finite`) and carry the key."""

class Model:
    """A wall of rigid blocks joined by zero-thickness Mohr-Coulomb interfaces.

    blocks: the wall's blocks [m]: an (n, 4) array of axis-aligned rectangles [x0, y0, x1, y1],
        or a list whose items are each a rectangle [x0, y0, x1, y1] or a convex polygon (a list
        of k >= 3 vertices [x, y], or a (k, 2) array, in either orientation). A concave stone is
        given as convex parts.
    thickness: out-of-plane thickness [m]; density [kg/m3].
    base: True puts a fixed rigid foundation under the lowest blocks, spanning the wall; None
        (the default): True unless supports are given.
    supports: fixed blocks (abutments, springers, an inclined plane) [m], as blocks: each a
        polygon (or a rectangle); the wall's joints with them are of the "base" family.
    gravity_direction: [gx, gy], the direction of gravity (made a unit vector), [0, -1] by
        default; the horizontal live load acts along it turned by +90 degrees ([1, 0] by default).
    top_rotation: None (no top beam), "fixed" or "free": a rigid, weightless beam resting on the
        highest blocks and spanning the wall; top_force: dead force [Fx, Fy] on it [N].
    top_vertical: "free" (the vertical force on the beam stays top_force[1]; the beam may rise) or
        "held" (the beam's vertical position is held once the dead loads are on, so the vertical
        force becomes a reaction that changes with the live load; quasi-static analyses only).
    joints: {family: law} with family in "default", "bed", "head", "base", "top"; a law is a dict
        with keys normal_stiffness [N/m3], shear_stiffness [N/m3], friction [-], cohesion [Pa],
        tensile_strength [Pa], dilatancy [-] (tan psi), fracture_energy_tension and
        fracture_energy_shear [N/m] (both 0: brittle, cohesion and tensile strength lost at the
        first failure; both > 0: exponential softening). Missing keys of a family law fall back
        to "default"; missing keys of "default" fall back to 1e10, 1e10, 0.65, 0, 0, 0, 0, 0.
    gravity [m/s2]; live: "horizontal_weight" (lambda * W_i on every block towards +x) or
        "top_horizontal" (lambda newtons on the top beam towards +x); +x: gravity_direction
        turned by +90 degrees.
    carried: loads carried by wall blocks (a floor's reaction), a list of (block, [x, y], weight):
        a weight [N] along gravity resting at a point [m] of the block (0-based), whose mass
        weight / gravity moves with it: it takes the live load in proportion to its weight, and
        the block's centroid (where its dofs are), mass and inertia are those of block and loads.
    Raises InputError naming the key, block or interface on bad input.
    """

    def __init__(
        self,
        blocks: npt.ArrayLike,
        thickness: Optional[float] = None,
        density: Optional[float] = None,
        base: Optional[bool] = None,
        top_rotation: Optional[Literal["fixed", "free"]] = None,  # None: no top beam
        top_force: Optional[Sequence[float]] = None,
        joints: Optional[dict[str, dict[str, float]]] = None,
        gravity: Optional[float] = None,
        live: Optional[Literal["horizontal_weight", "top_horizontal"]] = None,
        top_vertical: Optional[Literal["free", "held"]] = None,
        supports: Optional[Sequence[npt.ArrayLike]] = None,
        gravity_direction: Optional[Sequence[float]] = None,
        carried: Optional[Sequence[tuple[int, Sequence[float], float]]] = None,
    ) -> None: ...
    @property
    def carried(self) -> list[tuple[int, list[float], float]]:
        """The loads carried by wall blocks: a list of (block, [x, y], weight [N])."""
    @property
    def live(self) -> Literal["horizontal_weight", "top_horizontal"]:
        """The live load: "horizontal_weight" (lambda times each block's weight) or "top_horizontal" (lambda newtons on the top beam)."""
    def fix(self, block: int, dof: Literal[0, 1, 2], value: float = 0.0) -> None:
        """Fix dof (0: u1 [m], 1: u2 [m], 2: phi [rad]) of a block at a prescribed value."""
    @property
    def dimension(self) -> Literal[2]:
        """2: a wall in the plane (Model3D's is 3)."""
    @property
    def n_blocks(self) -> int:
        """Number of wall blocks (supports, base and top beam not counted)."""
    @property
    def n_interfaces(self) -> int:
        """Number of interfaces (the joints between blocks, and with the base and the top beam)."""
    @property
    def base_index(self) -> Optional[int]:
        """Index of the base (the fixed foundation) among the blocks; None without one."""
    @property
    def top_index(self) -> Optional[int]:
        """Index of the top beam among the blocks; None without one."""
    @property
    def default_control_block(self) -> int:
        """The block the solvers follow when no control block is given: the top beam if any, else the highest wall block at the right end."""
    @property
    def rects(self) -> FloatArray:
        """(n_all, 4) bounding box [x0, y0, x1, y1] of every block [m] (a rectangle's is itself), wall
        blocks first, then supports, then base, then top beam."""
    @property
    def polygons(self) -> list[FloatArray]:
        """Every block's polygon [m], a (k_i, 2) array of vertices counter-clockwise from the lowest
        (the leftmost of the lowest), in the order of rects: wall blocks, supports, base, top beam."""
    @property
    def centroids(self) -> FloatArray:
        """(n_all, 2) centroid of every block [m], where its dofs are: its centre of mass (the polygon's, moved by the loads it carries)."""
    @property
    def block_kinds(self) -> list[Literal["wall", "support", "base", "top"]]:
        """What each block is: "wall", "support", "base" or "top"."""
    @property
    def support_indices(self) -> list[int]:
        """Indices of the supports (the fixed blocks given) among the blocks."""
    @property
    def gravity_direction(self) -> list[float]:
        """[gx, gy]: the direction of gravity, a unit vector."""
    @property
    def weights(self) -> FloatArray:
        """(n_all,) weight of each block [N], with the loads it carries (0 for supports, base and top beam)."""
    @property
    def interface_blocks(self) -> IntArray:
        """(m, 2) block indices (a, b) of each interface; the normal points from a to b."""
    @property
    def interface_geometry(self) -> FloatArray:
        """(m, 5): centroid x, y [m], normal nx, ny, length l [m]."""
    @property
    def interface_family(self) -> list[str]:
        """Family of each interface: "bed", "head", "base" (with the base or a support) or "top"."""
    def solve_static(
        self,
        control: Optional[Literal["load", "displacement"]] = None,
        steps: Optional[int] = None,
        max_displacement: Optional[float] = None,
        control_block: Optional[int] = None,
        tolerance: Optional[float] = None,
        max_iterations: Optional[int] = None,
        progress: Optional[Callable[[int, float, float, float], None]] = None,
    ) -> "Results":
        """Static incremental analysis (Newton with the consistent tangent).

        Options left out (None) take the core's defaults: steps 200, tolerance 1e-4,
        max_iterations 50 (Newton iterations before a step is cut).

        control="load": raise lambda until collapse, following the equilibrium path in steps of
        the live load's work; the collapse multiplier is the peak or the plateau of lambda, to
        `tolerance` (relative). control="displacement": drive the horizontal displacement of
        control_block (default: the top beam if any, else the highest block at the right end;
        one held along x, the base, is refused) to max_displacement [m] in `steps` increments,
        through the peak and after it; without max_displacement (None), from 2 mm on by as much
        again, `steps` increments each time, until a peak or a plateau of lambda.
        Returns Results with status "collapse" (with its evidence: a peak, a plateau with no
        equilibrium just above, and on associative dry joints the limit-analysis multiplier),
        "completed" (the requested displacement reached, lambda still rising), "stalled" (load
        control stopped converging below the limit-analysis multiplier), "displacement_limit"
        (the path left the small-displacement model, a tenth of the wall's size, with lambda
        still rising) or "failed"; collapse_multiplier is NaN unless "collapse", and
        last_equilibrium holds the largest lambda found in equilibrium. Never raises for a
        solver failure (the reason is in Results.error).
        Runs in a thread of its own, the GIL released. Ctrl-C raises KeyboardInterrupt within a
        fraction of a second, with the partial Results as the exception's `results` attribute
        (None when the run is inside one long sparse factorization, 10^5 blocks and more: it
        then finishes that in the background and stops); an exception raised by `progress` is
        raised the same way.
        progress: optional callable(step, multiplier, displacement, fraction) called after each
        converged step (fraction in [0, 1] under displacement control, NaN otherwise)."""
    def solve_dynamic(
        self,
        control: Optional[Literal["load", "displacement"]] = None,
        steps: Optional[int] = None,
        max_displacement: Optional[float] = None,
        control_block: Optional[int] = None,
        tolerance: Optional[float] = None,
        unbalanced_ratio: Optional[float] = None,
        damping: Optional[Literal["local", "viscous", "none"]] = None,
        damping_coefficient: Optional[float] = None,
        time_step: Optional[float] = None,
        safety: Optional[float] = None,
        threads: Optional[int] = None,
        large_rotations: Optional[bool] = None,
        contact_update: Optional[bool] = None,
        progress: Optional[Callable[[int, float, float, float], None]] = None,
        move_support: Optional[int] = None,
        move_direction: Optional[Literal["+x", "-x", "+y", "-y"]] = None,
    ) -> "Results":
        """Quasi-static analysis with the explicit (molecular dynamics) solver; the same Results
        as solve_static, with method "dynamic" and `iterations` = time steps.

        Options left out (None) take the core's defaults: steps 200, max_displacement 0.002 m,
        tolerance 1e-3, unbalanced_ratio 1e-5, damping "local" with coefficient 0.8, safety 0.8,
        threads 0 (all cores).

        control="load": each load level is relaxed until |unbalanced| <= unbalanced_ratio *
        |applied|; the collapse multiplier is bracketed to `tolerance`. control="displacement":
        the control block is driven to max_displacement in `steps` stages, lambda following from
        its equation. damping: "local" (Cundall, coefficient alpha in [0, 1)), "viscous"
        (mass-proportional, coefficient c [1/s]) or "none". time_step [s]: None for the automatic
        stable step (safety * the stability limit); a user step above the limit is an InputError.
        threads: threads of the interface loop (0: all cores). large_rotations: finite rotations
        of the blocks, each stage's equilibrium found on the moved geometry (the
        large-displacement capacity curve under displacement control; its drive is quasi-static
        in small stages only: keep steps at 200 or more); default False, the linearized
        kinematics. contact_update: the contacts found again as the blocks move, as in
        Model.simulate (large_rotations=True needed); default False. Status and multipliers as in
        solve_static (here the path always ends at max_displacement, default 2 mm). Releases the
        GIL; Ctrl-C raises KeyboardInterrupt with the partial Results as its `results` attribute.
        progress: as in solve_static, every few thousand steps.

        move_support with move_direction (as in solve_limit): that support driven along the
        direction by max_displacement [m] (> 0, required) in `steps` stages under
        control="displacement" (the default then), each relaxed with the support held; the wall
        falls at the first stage that does not settle (a block moving 1% of the model's size, or
        the unbalanced ratio not settling within the steps allowed): status "collapse" with
        `bracket` the movements of the last stage that settled and of the first that did not,
        else "completed". The curve: the support's movement [m] and the force the wall exerts on
        it along the movement [N] (from the dead state); large_rotations=True follows the moved
        geometry."""
    def solve_limit(
        self,
        tolerance: Optional[float] = None,
        max_iterations: Optional[int] = None,
        max_sequence: Optional[int] = None,
        progress: Optional[Callable[[int, float, float, float], None]] = None,
        follow_mechanism: bool = False,
        follow_step: Optional[float] = None,
        follow_steps: Optional[int] = None,
        move_support: Optional[int] = None,
        move_direction: Optional[Literal["+x", "-x", "+y", "-y"]] = None,
    ) -> "Results":
        """Limit analysis (the static theorem): the largest lambda for which interface forces inside
        the joints' strength domains balance the dead loads plus lambda times the live load, as a
        linear program solved by a primal-dual interior point method on the stiffness matrix's
        sparsity pattern. Exact for dry associative joints (dilatancy = friction); for dilatancy
        below friction the associative optimum is an upper bound (certificate["upper_bound"]) and
        the multiplier is a non-associative estimate from a sequence of at most max_sequence
        programs (0: the associative bound only), status "estimate": neither bound, converged or
        not, its value in last_equilibrium and certificate["multiplier"], the bound in
        certificate["upper_bound"], the convergence in certificate["sequence_converged"].
        Mortar joints enter with their peak strengths.

        tolerance: the interior point stops when its scaled residuals and relative duality gap are
        all below this (0 < tolerance < 0.01; default 1e-8). max_iterations: interior-point
        iterations per program (default 200); max_sequence default 50.
        Returns Results with method "limit" and status "collapse" (collapse_multiplier, the
        mechanism's normalised block velocities in `mechanism`, the forces at collapse in
        interface_forces, the crack pattern in interface_states), "no_equilibrium" (the dead loads
        alone cannot be carried), "unbounded" (no mechanism within the range of multipliers),
        "estimate" (dilatancy below friction, see above) or "failed" (the interior point did not
        converge); the reason is in Results.error, and
        collapse_multiplier is NaN unless the status is "collapse". No load path: the curve is
        empty, displacements are zeros and steps is 0; iterations counts interior-point iterations.
        Releases the GIL; Ctrl-C stops it between iterations and raises KeyboardInterrupt, whose
        `results` attribute is a Results with status "failed" and error "interrupted by the
        user" (no multiplier, no certificate).
        progress: optional callable(iteration, multiplier, nan, nan) called after each
        interior-point iteration (iterations counted over all the programs; multiplier: the
        current estimate). An exception raised by it stops the analysis and is raised again.

        follow_mechanism=True: the collapse mechanism is then followed to the end, the blocks
        moved by finite steps of it (each turned exactly about its instantaneous centre), the
        contacts found again (along edges and at points) and the limit analysis solved again on
        the moved geometry: the large-displacement capacity curve. The Results are the first
        analysis's (multiplier, mechanism, certificate) with `curve_displacement` (the control
        block's horizontal displacement [m]) and `curve_multiplier` (lambda on the moved geometry)
        from (0, lambda_0) down to lambda = 0, `displacements` the blocks' finite motion at the
        curve's end (u1, u2 [m], phi [rad]) and `steps` the steps taken; a curve that stops short
        of zero says why in Results.error (the status stays the first analysis's). follow_step:
        the largest displacement of a block's vertex in one step [m] (default: the model's size
        over 200); a step that fails is halved. follow_steps: steps at most (default 1000).

        move_support (0-based among the supports; an arch's abutments 0 and 1) with
        move_direction ("+x", "-x", "+y" or "-y"): that support moved along the direction (its
        dof made free, a unit force on it the live load), followed to where no equilibrium exists
        (follow_step default: the model's size over 1000). lambda is then the force the wall
        exerts on the support along its movement [N] (an arch's thrust against a spread), the
        least of every admissible state: collapse_multiplier its value as built,
        curve_displacement the support's movement [m], curve_multiplier the force on the moved
        geometry, last_equilibrium the force at the curve's end. Status "collapse" where a moved
        geometry within a step past the end has no equilibrium at any force on the support (the
        wall falls there), "completed" (the steps ran out) or "failed" (no such proof), with the
        reason in Results.error."""
    def simulate(
        self,
        duration: float,
        time_step: Optional[float] = None,
        safety: Optional[float] = None,
        damping: Optional[Literal["local", "viscous", "none"]] = None,
        damping_coefficient: Optional[float] = None,
        initial_displacements: Optional[npt.ArrayLike] = None,
        initial_velocities: Optional[npt.ArrayLike] = None,
        base_acceleration: Optional[tuple[npt.ArrayLike, npt.ArrayLike]] = None,
        live_multiplier: Optional[float] = None,
        record_every: Optional[int] = None,
        large_rotations: Optional[bool] = None,
        threads: Optional[int] = None,
        progress: Optional[Callable[[int, float, float, float], None]] = None,
        vertical_acceleration: Optional[tuple[npt.ArrayLike, npt.ArrayLike]] = None,
        record_interval: Optional[float] = None,
        rayleigh: Optional[tuple[float, float]] = None,
        contact_update: Optional[bool] = None,
    ) -> "TimeHistory":
        """Time history with the explicit solver. Options left out (None) take the core's
        defaults: safety 0.8, damping "none" (coefficient 0), live_multiplier 0, a record every
        record_interval = 0.001 s, large_rotations True, threads 0 (all cores).

        Free motion from initial conditions
        (initial_displacements / initial_velocities: (n_all, 3) arrays of u1 [m], u2 [m],
        phi [rad] and their rates) and/or the ground's motion: base_acceleration (horizontal) and
        vertical_acceleration (upwards), each (times [s], accelerations [m/s2]), linear between
        samples and zero outside them; the blocks move in the frame of the base (displacements
        relative to the ground). live_multiplier: lambda held constant. large_rotations: block
        kinematics with finite rotations (needed for rocking); False uses the linearized
        kinematics of the static solver. Impacts lose energy by the joints' restitution (joint
        key "restitution", default 0.3: Housner's impact of a rocking block); the time step
        is lowered for the contact dashpots this takes. rayleigh=(alpha [1/s], beta [s]): Rayleigh
        damping alpha M + beta K (masonry_dem.rayleigh_damping from two modes), the beta K part as
        dashpots at the closed interfaces; instead of damping / damping_coefficient. Records every record_interval seconds
        or every record_every-th step (not both); Model.record_size gives the memory up front.
        contact_update (default True, with large_rotations; False: the contacts of the wall as built): the contacts found again as the
        blocks move (new contacts dry, with the joints' restitution; a contact found again keeps
        its history) and a ground plane at the top of the base (without a base, at the lowest
        point), reaching five model sizes beyond the blocks, onto which falling blocks come to rest.
        Releases the GIL; Ctrl-C stops it and raises KeyboardInterrupt, with the TimeHistory
        computed so far as its `results` attribute.
        progress: optional callable(step, time [s], nan, fraction done)."""
    def record_size(
        self,
        duration: float,
        time_step: Optional[float] = None,
        record_every: Optional[int] = None,
        record_interval: Optional[float] = None,
    ) -> tuple[int, float]:
        """(records, bytes) that Model.simulate with these options would hold (its time step as
        simulate chooses it); refuses what simulate refuses."""
    def critical_time_step(self, time_history: bool = False, contact_update: bool = True) -> float:
        """The stability limit of the explicit solver's time step [s] (Gershgorin bound); with
        time_history=True, that of Model.simulate: lowered for the contact dashpots of the
        joints' restitution (the factor sqrt(1 + z^2) - z with z = 3 zeta, zeta the dashpot's
        damping ratio) and, with contact_update (True, simulate's default), for a block touching
        fixed bodies along every edge."""

class Model3D:
    """A wall of rigid blocks in 3D (axis-aligned boxes and convex polyhedra), z up, joined by dry Mohr-Coulomb contacts
    (limit analysis, the explicit solver and time histories).

    boxes: (n, 6) array of boxes [x0, y0, z0, x1, y1, z1] in m (running_bond_3d, u_wall, corner_wall); None or
        left out with polyhedra only.
    density [kg/m3] of the blocks and the top beam (default 2000).
    base: True (the default) puts a fixed rigid foundation under the wall's footprint (the box around the blocks in
        plan, as deep as the tallest block); the lowest blocks stand on it.
    top: None (the default: no top beam) or the height [m] of a rigid top beam of the blocks' density over the box
        around the blocks in plan, resting on the highest blocks, free to move; it weighs and takes the live load.
    joints: as Model's, {family: law} with family in "default", "bed", "head", "base", "top"; the 3D analyses take
        joints with cohesion and tensile_strength too (brittle: fracture energies 0; shared by a contact's corners by
        tributary area): limit analysis reads their strengths, friction and dilatancy, the explicit solver the
        stiffnesses too (and restitution, in time histories).
    gravity [m/s2], along -z (default 9.81); live: "horizontal_weight" (the default: lambda * W_i on every block
        that weighs, horizontal) or "none"; direction: the live load's direction in plan [deg], from +x towards +y
        (default 0: towards +x; 90 pushes a facade along x out of its plane, towards +y).
    carried: loads carried by wall blocks (a floor's reaction), a list of (block, [x, y, z], weight): a weight [N]
        along -z resting at a point [m] of the box (0-based), whose mass weight / gravity moves with it, as Model's.
        A time history refuses a load off the box's axes through its centroid (its products of inertia).
    polyhedra: wall blocks of any convex shape after the boxes, a list of vertex lists (each a (k, 3) array or a
        list of [x, y, z] rows [m]): each block the convex hull of its vertices (at least 4 off one plane).
    supports: fixed blocks of any convex shape, vertex lists as polyhedra (an abutment, an inclined plane); with
        supports the default base is False (no foundation unless base=True).
    Block indices: the boxes in the order given, then the polyhedra, then the base, then the top beam, then the
    supports. Raises InputError naming the key or block on bad input (`polyhedra[3]: ...` for a list that makes no
    convex block; two overlapping blocks are both named)."""

    def __init__(
        self,
        boxes: Optional[npt.ArrayLike] = None,
        density: Optional[float] = None,
        base: Optional[bool] = None,
        top: Optional[float] = None,  # None: no top beam; else its height [m]
        joints: Optional[dict[str, dict[str, float]]] = None,
        gravity: Optional[float] = None,
        live: Optional[Literal["horizontal_weight", "none"]] = None,
        direction: Optional[float] = None,
        carried: Optional[Sequence[tuple[int, Sequence[float], float]]] = None,
        polyhedra: Optional[Sequence[npt.ArrayLike]] = None,
        supports: Optional[Sequence[npt.ArrayLike]] = None,
    ) -> None: ...
    @property
    def dimension(self) -> Literal[3]:
        """3: a wall of boxes in 3D (Model's is 2)."""
    @property
    def carried(self) -> list[tuple[int, list[float], float]]:
        """The loads carried by wall blocks: a list of (block, [x, y, z], weight [N])."""
    @property
    def live(self) -> Literal["horizontal_weight", "none"]:
        """The live load: "horizontal_weight" (lambda times each block's weight, horizontal, along direction) or "none"."""
    @property
    def direction(self) -> Optional[float]:
        """The live load's direction in plan [deg], from +x towards +y; None without a live load."""
    @property
    def gravity(self) -> float:
        """Acceleration of gravity [m/s2], along -z."""
    @property
    def n_blocks(self) -> int:
        """Number of wall blocks (base and top beam not counted), as Model.n_blocks."""
    @property
    def n_interfaces(self) -> int:
        """Number of interfaces (the contacts between blocks, and with the base and the top beam)."""
    @property
    def base_index(self) -> Optional[int]:
        """Index of the base (the fixed foundation) among the blocks; None without one."""
    @property
    def top_index(self) -> Optional[int]:
        """Index of the top beam among the blocks; None without one."""
    @property
    def boxes(self) -> FloatArray:
        """(n_all, 6) boxes [x0, y0, z0, x1, y1, z1] of all blocks [m], wall blocks first, then base, then top beam, then
        supports; a polyhedron's is the box around it (block_vertices and block_faces give its shape)."""
    @property
    def centroids(self) -> FloatArray:
        """(n_all, 3) centroid of each block [m] (where its dofs are and its moments are taken): its centre of mass (the box's centre, moved by the loads it carries)."""
    @property
    def mass(self) -> FloatArray:
        """(n_all,) mass of each block [kg], with the loads it carries (the base's too, though it is fixed)."""
    @property
    def weights(self) -> FloatArray:
        """(n_all,) weight of each block [N], with the loads it carries (the wall's and the top beam's; 0 for the base)."""
    @property
    def interface_blocks(self) -> IntArray:
        """(m, 2) block indices (a, b) of each interface; the normal points from a to b."""
    @property
    def interface_normals(self) -> FloatArray:
        """(m, 3) unit normal of each interface, from block a into block b (+x, +y or +z)."""
    @property
    def interface_t1(self) -> FloatArray:
        """(m, 3) first unit tangent t1 of each interface: +x on a horizontal one, the horizontal tangent on a vertical one."""
    @property
    def interface_t2(self) -> FloatArray:
        """(m, 3) second unit tangent t2 = normal x t1 of each interface (+y on a horizontal one, +z on a vertical one)."""
    @property
    def interface_centroids(self) -> FloatArray:
        """(m, 3) centroid of each interface [m]."""
    @property
    def interface_corners(self) -> FloatArray:
        """(m, 4, 3) corners of each interface's rectangle [m], counter-clockwise seen from the tip of its normal (a
        polygon of other than four corners padded with NaN or cut to four: interface_polygons gives them all)."""
    @property
    def interface_polygons(self) -> list[FloatArray]:
        """Each interface's polygon [m]: a list of (k, 3) arrays, its k >= 3 corners counter-clockwise seen from the tip
        of its normal (between boxes the rectangle of interface_corners; between polyhedra any convex polygon, whose
        corners interface_corners cuts to four)."""
    @property
    def block_vertices(self) -> list[FloatArray]:
        """Each block's vertices [m] (wall blocks, base, top beam, supports, as boxes): a list of (k, 3) arrays."""
    @property
    def block_faces(self) -> list[list[list[int]]]:
        """Each block's faces: per block a list of faces, each the indices of its vertices in block_vertices,
        counter-clockwise seen from outside."""
    @property
    def block_is_box(self) -> list[bool]:
        """Whether each block is a box with sides along the axes (its row of boxes is the block itself, not the box
        around it)."""
    @property
    def interface_areas(self) -> FloatArray:
        """(m,) area of each interface [m2]."""
    @property
    def interface_family(self) -> list[str]:
        """Family of each interface: "bed", "head", "base" or "top"."""
    def solve_limit(
        self,
        tolerance: Optional[float] = None,
        max_iterations: Optional[int] = None,
        threads: Optional[int] = None,
        progress: Optional[Callable[[int, float, float, float], None]] = None,
        along_gravity: bool = False,
        follow_mechanism: bool = False,
        follow_step: Optional[float] = None,
        follow_steps: Optional[int] = None,
    ) -> "Results":
        """Limit analysis in 3D (the static theorem): the largest lambda for which contact forces inside the joints'
        strength domains balance the dead loads plus lambda times the live load, a second-order cone program solved
        by the interior point of Model.solve_limit. Each corner of a contact carries a force in Coulomb's cone
        (|T| <= mu N, the same in every direction of sliding, as in solve_dynamic); torsion and biaxial bending come
        from the corners' positions. Mortar joints (cohesion, tensile_strength) enter with their peak strengths. Refused
        a wall that nothing holds (no base, or blocks that no chain of contacts joins to it). Exact for dry associative joints (dilatancy = friction), status
        "collapse"; for dilatancy below friction the associative optimum, an upper bound, with status "estimate".

        tolerance: the interior point's stopping tolerance (0 < tolerance < 0.01; default 1e-8); max_iterations:
        interior-point iterations (default 200). Returns Results with dimension 3, method "limit": the mechanism's
        block velocities (vx, vy, vz, wx, wy, wz; largest block translation 1) in `mechanism`, the contact forces at
        collapse (N, T1, T2, M_n, M_t1, M_t2) in interface_forces, the crack pattern in interface_states; statuses as
        Model.solve_limit. Releases the GIL; Ctrl-C stops it between iterations and raises KeyboardInterrupt, whose
        `results` attribute is a Results with status "interrupted" (no multiplier, no certificate).
        threads: threads of the interior point's passes over contacts from 2,000 contacts (below, one; default 0: all
        cores); the results are the same to the bit with any number.
        progress: optional callable(iteration, multiplier, nan, nan) called after each interior-point iteration; an
        exception raised by it stops the analysis and is raised again.
        along_gravity: True takes lambda times the weights along gravity as the live load instead of the model's (lambda
        a factor on the self-weight): the wall stands under its own weight if the status is "unbounded", and not if it
        is "no_equilibrium" (near a least thickness better posed than the sign of the horizontal multiplier).
        follow_mechanism=True: the collapse mechanism is then followed to the end, as Model.solve_limit's: the blocks
        moved by finite steps of it (each by the screw motion of its velocities: turned exactly about its
        instantaneous axis, a hinge edge's rotation exact), the contacts found again (over polygons, along edges and at
        points) and the limit analysis solved again on the moved geometry. `curve_displacement` is the control block's
        (the highest wall block's) displacement along the live load's direction in plan [m], `curve_multiplier` lambda on
        the moved geometry, `displacements` the blocks' finite motion at the curve's end (ux, uy, uz [m], then the
        rotation vector rx, ry, rz [rad]: the angle about its axis), `steps` the steps taken; a curve that stops short of
        zero says why in Results.error. follow_step [m] and follow_steps as in Model.solve_limit; refused with
        along_gravity."""
    def solve_dynamic(
        self,
        control: Optional[Literal["load"]] = None,
        steps: Optional[int] = None,
        max_displacement: Optional[float] = None,
        control_block: Optional[int] = None,
        tolerance: Optional[float] = None,
        unbalanced_ratio: Optional[float] = None,
        damping: Optional[Literal["local", "viscous", "none"]] = None,
        damping_coefficient: Optional[float] = None,
        time_step: Optional[float] = None,
        safety: Optional[float] = None,
        threads: Optional[int] = None,
        large_rotations: Optional[bool] = None,
        contact_update: Optional[bool] = None,
        progress: Optional[Callable[[int, float, float, float], None]] = None,
    ) -> "Results":
        """Quasi-static analysis in 3D with the explicit solver: Model.solve_dynamic's on the wall of boxes, with the same
        options (and defaults) and Results of dimension 3, method "dynamic", `iterations` = time steps. Each corner of a
        contact is a point with the joint law (a normal force that never pulls, with the rectangle's elastic stiffness,
        and a shear force within Coulomb's cone);
        the blocks' rotations are small, as in limit analysis. Load control only: each load level is relaxed until
        |unbalanced| <= unbalanced_ratio * |applied|, and the collapse multiplier is bracketed to `tolerance`
        (Results.bracket: the highest level that settled, the lowest that ran away); control="displacement" is
        refused (InputError), and so is a wall that nothing holds; joints with strength are brittle (fracture energies 0).
        The curve follows control_block (default: the highest wall block) along x, or along y when the live load's
        direction is nearer y; a control block held along that axis (the base) is refused. damping,
        damping_coefficient, time_step [s], safety, unbalanced_ratio, threads: as in Model.solve_dynamic
        (Model3D.critical_time_step gives the stability limit); large_rotations=True and contact_update=True are
        refused (InputError): a 3D pushover is on the wall as built. Releases the GIL; Ctrl-C raises KeyboardInterrupt
        with the partial Results as its `results` attribute. progress: as in Model.solve_dynamic."""
    def simulate(
        self,
        duration: float,
        time_step: Optional[float] = None,
        safety: Optional[float] = None,
        damping: Optional[Literal["local", "viscous", "none"]] = None,
        damping_coefficient: Optional[float] = None,
        initial_displacements: Optional[npt.ArrayLike] = None,
        initial_velocities: Optional[npt.ArrayLike] = None,
        base_acceleration: Optional[tuple[npt.ArrayLike, npt.ArrayLike]] = None,
        live_multiplier: Optional[float] = None,
        record_every: Optional[int] = None,
        large_rotations: Optional[bool] = None,
        threads: Optional[int] = None,
        progress: Optional[Callable[[int, float, float, float], None]] = None,
        vertical_acceleration: Optional[tuple[npt.ArrayLike, npt.ArrayLike]] = None,
        record_interval: Optional[float] = None,
        rayleigh: Optional[tuple[float, float]] = None,
        base_acceleration_y: Optional[tuple[npt.ArrayLike, npt.ArrayLike]] = None,
        contact_update: Optional[bool] = None,
    ) -> "TimeHistory":
        """Time history of the wall of boxes with the explicit solver: Model.simulate's options (and defaults), in 3D.
        Free motion from initial conditions (initial_displacements / initial_velocities: (n_all, 6) arrays of ux, uy,
        uz [m] and a rotation vector rx, ry, rz [rad], and their rates: the angular velocity in the world's axes
        [rad/s]) and/or the ground's motion: base_acceleration (along x), base_acceleration_y (along y) and
        vertical_acceleration (upwards), each (times [s], accelerations [m/s2]), linear between samples and zero
        outside them; the blocks move in the frame of the base. Finite rotations (unit quaternions, Euler's
        equations) unless large_rotations is False. Impacts lose energy by the joints' restitution (the time step is
        lowered for the contact dashpots this takes). Joints with strength are brittle (fracture energies 0);
        damping "local", "viscous" or "none": stiffness-proportional damping is the plane's only (rayleigh takes
        beta = 0 only). Returns a TimeHistory of dimension 3, with the ground's acceleration and the base shear along
        y too. Releases the GIL; Ctrl-C stops it and raises KeyboardInterrupt, with the TimeHistory computed so far
        as its `results` attribute. progress: optional callable(step, time [s], nan, fraction done).
        contact_update (default True, with large_rotations; False: the contacts of the wall as built): the contacts
        found again as the blocks move (faces
        facing within the gap tolerance; new contacts dry, with the joints' restitution; a contact found again keeps
        its history) and a ground plane at the top of the base (without a base, at the lowest point), reaching five
        model sizes beyond the blocks in plan, onto which falling blocks come to rest."""
    def record_size(
        self,
        duration: float,
        time_step: Optional[float] = None,
        record_every: Optional[int] = None,
        record_interval: Optional[float] = None,
    ) -> tuple[int, float]:
        """(records, bytes) that Model3D.simulate with these options would hold (its time step as simulate chooses
        it), as Model.record_size; refuses what simulate refuses of them."""
    def critical_time_step(self, time_history: bool = False, contact_update: bool = True) -> float:
        """The stability limit of the explicit solver's time step in 3D [s] (Gershgorin bound on the contact points'
        elastic stiffnesses), as Model.critical_time_step(); with time_history=True, that of Model3D.simulate:
        lowered for the contact dashpots of the joints' restitution and, with contact_update (True, simulate's
        default), for a block touching fixed bodies along every face."""

class TimeHistory:
    """A time history (Model.simulate, Model3D.simulate). Energy balance at each record: initial kinetic + elastic
    energy + external_work = kinetic_energy + elastic_energy + dissipated + energy_error. One class for both
    dimensions: the block arrays have 3 columns in the plane (dimension 2) and 6 in 3D (dimension 3)."""

    dimension: Literal[2, 3]
    """2 for a wall in the plane (Model.simulate), 3 for a wall of boxes (Model3D.simulate): the block arrays have
    3 or 6 columns."""
    status: str
    """How the run ended: "completed", "failed" or "interrupted"."""
    error: Optional[str]
    """Why, when the status is "failed" or "interrupted" (None otherwise)."""
    time_step: float
    """The time step used [s]."""
    times: FloatArray
    """(k,) time of each record [s]."""
    displacements: FloatArray
    """(k, n_all, 3): u1 [m], u2 [m], phi [rad], relative to the ground; in 3D (k, n_all, 6): ux, uy, uz [m] and
    rx, ry, rz [rad], the rotation vector of the block's orientation."""
    velocities: FloatArray
    """(k, n_all, 3): du1/dt [m/s], du2/dt [m/s], dphi/dt [rad/s], relative to the ground; in 3D (k, n_all, 6):
    vx, vy, vz [m/s] and the angular velocity wx, wy, wz [rad/s] in the world's axes."""
    ground_acceleration: FloatArray
    """(k, 2) the ground's (horizontal, vertical) acceleration [m/s2]; in 3D the horizontal one along x."""
    ground_acceleration_y: FloatArray
    """(k,) 3D: the ground's acceleration along y [m/s2]; (0,) in the plane."""
    base_shear: FloatArray
    """(k,) horizontal force of the wall on its base [N] (+x positive)."""
    base_shear_y: FloatArray
    """(k,) 3D: the force of the wall on its base along y [N] (+y positive); (0,) in the plane."""
    kinetic_energy: FloatArray
    """(k,) kinetic energy of the blocks [J]."""
    elastic_energy: FloatArray
    """(k,) energy stored in the joints [J]."""
    external_work: FloatArray
    """(k,) work of the external loads since t = 0 (weights, loads, base motion) [J]."""
    gravity_work: FloatArray
    """(k,) the weights' part of external_work [J]."""
    friction_dissipation: FloatArray
    """(k,) dissipated by friction and loss of strength in the joints [J]."""
    damping_dissipation: FloatArray
    """(k,) dissipated by the damping of the motion (local, viscous, Rayleigh) [J]."""
    impact_dissipation: FloatArray
    """(k,) dissipated by impacts (the joints' restitution) [J]."""
    dissipated: FloatArray
    """(k,) the three dissipations together [J]."""
    energy_error: FloatArray
    """(k,) the balance's error [J]."""
    steps: int
    """Time steps computed."""
    elapsed_s: float
    """Wall-clock time of the run [s]."""
    contact_counts: Tuple[int, int, int, int]
    """With the contact update (Model.simulate(contact_update=True), the default): the searches for contacts made,
    and the contacts created, dropped, and taken again from the moved blocks; zeros without it."""
    ground_level: Optional[float]
    """With the contact update: the ground plane's level [m], if the model has one (None otherwise)."""
    contact_events: Dict[str, Any]
    """With the contact update: every contact created, dropped or taken again, in order, as a dict of arrays (empty
    without it): "time" [s], "change" ("created", "dropped", "renewed"), "id" (the contact's number: the model's
    interfaces 0..m in their order, then each created contact in turn), "blocks" (n, 2) (a: the block whose edge
    gives the normal), "centre" (n, 2) [m] relative to block a's centroid and "normal" (n, 2) from a into b, both
    in a's position at rest (a block's displacement carries them), "length" [m]; a dropped contact has zero
    geometry. With Model.interface_blocks / interface_geometry they give the contacts at any time
    (masonry_dem.history.contacts_at)."""

class _Certificate(TypedDict):
    """What a limit analysis certifies (Results.certificate)."""

    multiplier: Optional[float]  # the program's collapse multiplier (None when it has none)
    primal_residual: float  # largest violation of equilibrium or of a strength face, relative to the loads
    dual_residual: float  # largest violation of the dual (mechanism) equations
    duality_gap: float  # relative difference of the primal and dual objectives
    iterations: int  # interior-point iterations in all
    upper_bound: Optional[float]  # the associative multiplier when dilatancy < friction somewhere, else None
    sequence: int  # programs of the non-associative sequence after the associative one (0: none)
    sequence_converged: bool  # whether the sequence's multiplier settled within its tolerance
    peak_strengths: bool  # some joint has cohesion or tensile strength, taken at its peak (no softening)

class Results:
    """The results of an analysis (Model.solve_static, solve_dynamic, solve_limit; Model3D.solve_dynamic, solve_limit):
    the curve of the live load's multiplier lambda [-] against the control block's displacement [m], the
    displacements [m, rad] and the joints' forces [N, N m] and states at the end, and the collapse multiplier. One
    class for both dimensions: the block and interface arrays have 3 columns in the plane (dimension 2) and 6 in 3D
    (dimension 3)."""

    dimension: Literal[2, 3]
    """2 for a wall in the plane (Model), 3 for a wall of boxes (Model3D): the block and interface arrays have 3 or
    6 columns."""
    method: str
    """The solver: "static", "dynamic" or "limit"."""
    status: str
    """How the analysis ended: "collapse", "completed", "failed", "interrupted", "unbounded", "no_equilibrium" or
    "estimate" (limit), "stalled" or "displacement_limit" (static)."""
    error: Optional[str]
    """Why, when the status is "failed", "no_equilibrium", "unbounded", "stalled" or "displacement_limit"; what the
    number is, with "estimate"."""
    collapse_multiplier: float
    """Lambda at collapse, or the peak of the curve; NaN unless the status is "collapse"."""
    last_equilibrium: float
    """The largest lambda found in equilibrium (load control: the last step), whatever the status (the estimate, with
    "estimate"); NaN if none."""
    bracket: Optional[Tuple[float, float]]
    """Explicit load control ending in a collapse: (highest level that settled, lowest that ran away), the collapse
    multiplier being the first; None otherwise."""
    curve_multiplier: FloatArray
    """(k,) lambda at each converged step, from 0 (empty for "limit")."""
    curve_displacement: FloatArray
    """(k,) horizontal displacement of the control point [m] (empty for "limit"); in 3D along x, or along y when the
    live load's direction is nearer y."""
    control_block: int
    """The block whose horizontal displacement the curve follows (Model.default_control_block unless given; in 3D the
    highest wall block unless given)."""
    displacements: FloatArray
    """(n_all, 3): u1 [m], u2 [m], phi [rad] at the last converged step (zeros for "limit"); in 3D (n_all, 6): ux, uy,
    uz [m], rx, ry, rz [rad] (small rotations about the block's centroid)."""
    mechanism: FloatArray
    """(n_all, 3): last increment (limit: the block velocities), scaled so that max |u| is 1; in 3D (n_all, 6): the
    velocities (vx, vy, vz, wx, wy, wz) of the collapse mechanism (dynamic: the motion at the level that ran
    away), its largest block translation 1."""
    interface_forces: FloatArray
    """(m, 3): N [N] (tension > 0), T [N], M [N m] (limit: at collapse); in 3D (m, 6): N, T1, T2 [N], M_n, M_t1,
    M_t2 [N m], the force and moment (about the contact's centroid) of block b on block a in the contact's axes
    (normal, t1, t2), N > 0 in tension."""
    interface_states: IntArray
    """(m,) bit flags: 1 open, 2 sliding, 4 rocking; 0 elastic (limit: of the mechanism)."""
    broken: npt.NDArray[np.bool_]
    """(m,) bool: the joint lost its cohesion and tensile strength."""
    joint_states: dict[str, int]
    """Counts of the interfaces by state: {"elastic": n, "sliding": n, "rocking": n, "open": n}."""
    iterations: int
    """Total equilibrium iterations (static), time steps (dynamic), interior-point iterations (limit)."""
    steps: int
    """Converged steps (0 for "limit")."""
    elapsed_s: float
    """Wall-clock time of the analysis [s]."""
    certificate: Optional[_Certificate]
    """What a limit analysis certifies, as a dict (keys: multiplier, primal_residual, dual_residual, duality_gap,
    iterations, upper_bound, sequence, sequence_converged, peak_strengths): a limit analysis's own, or that of the
    check of a static load-control run on associative dry joints; None otherwise."""

class Modes:
    """The natural modes of a model's elastic joints (``modes``), lowest frequency first."""

    frequencies_hz: FloatArray
    """(n,) natural frequencies [Hz]."""
    angular_frequencies: FloatArray
    """(n,) angular frequencies [rad/s]; 0 for a mode of no stiffness (a mechanism)."""
    eigenvalues: FloatArray
    """(n,) omega^2 as computed [rad2/s2]."""
    shapes: FloatArray
    """(n, n_all, 3): u1, u2, phi of every block (as Model.rects); in 3D (n, n_all, 6): ux, uy, uz, rx, ry,
    rz. phi^T M phi = 1, fixed dofs 0."""
    dimension: int
    """2 for the modes of a wall in the plane (Model), 3 for those of a 3D model (Model3D)."""
    residuals: FloatArray
    """(n,) ||K phi - omega^2 M phi|| / ||K phi||."""
    effective_mass: FloatArray
    """(n, 2) effective modal masses along x and y [kg]; in 3D (n, 3), along x, y and z."""
    free_mass: tuple[float, ...]
    """The mass free to move along x and y [kg] (in 3D along x, y and z): the effective masses' sum over all
    modes."""
    shift: float
    """The shift sigma of the operator (K - sigma M)^-1 M [rad2/s2]."""
    basis: int
    """Size of the Lanczos basis."""
    def __len__(self) -> int: ...

def modes(model: Union[Model, Model3D], n: int, shift: Optional[float] = None) -> Modes:
    """The n lowest natural modes of the model's elastic joints (K phi = omega^2 M phi on the free dofs), or
    with a shift [rad2/s2] the n whose omega^2 are nearest to it; the model a Model or a Model3D. Releases the
    GIL."""

def rayleigh(f1_hz: float, f2_hz: float, zeta1: float, zeta2: Optional[float] = None) -> tuple[float, float]:
    """Rayleigh damping C = alpha M + beta K: (alpha [1/s], beta [s]) giving the damping ratio zeta1 at f1_hz
    and zeta2 (default zeta1) at f2_hz [Hz]."""
