//! The wall generators: `running_bond` and `pattern`, and those of convex polygons: `arch`, `gable` and
//! `stone_wall`.

use crate::*;

/// Blocks [x0, y0, x1, y1] (shape (n, 4), m) of a running-bond wall standing at y = 0 from x = 0.
///
/// block_length, block_height: a whole block's size [m]; length: the wall's length [m] (required).
/// Exactly one of courses (whole courses) and height (the wall's height [m]): with height, the whole
/// courses that fit and, if more is left, a last course cut to the remainder; a remainder under 25%
/// of block_height is refused, the message naming the nearest heights and block heights that fit.
/// Courses alternate between starting with a half block ("half") and a whole block ("full");
/// a block that would cross x = length is cut there. Openings [x0, y0, x1, y1] (in m) are cut out:
/// a block partly inside one is cut at its edges into the parts outside it (straight jambs, sill
/// and lintel; exactly the opening's area removed), an edge within 5% of a block's size of a joint
/// being moved onto the joint so that no sliver of a block is made.
#[pyfunction]
#[pyo3(signature = (block_length, block_height, courses=None, length=None, first_course=None, openings=None, *, height=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn running_bond<'py>(
    py: Python<'py>,
    block_length: f64,
    block_height: f64,
    courses: Option<i64>,
    length: Option<f64>,
    first_course: Option<&str>,
    openings: Option<&Bound<'py, PyAny>>,
    height: Option<f64>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let first_course = first_course.map_or(Ok(FirstCourse::default()), str::parse).map_err(to_py)?;
    let Some(length) = length else {
        return Err(InputError::new_err(
            "geometry.running_bond.length is required: the length of the wall [m]",
        ));
    };
    let courses = match (courses, height) {
        (Some(n), _) if n < 1 => {
            return Err(InputError::new_err(format!(
                "geometry.running_bond.courses must be at least 1, got {n}"
            )))
        }
        (None, None) => {
            return Err(InputError::new_err(
                "geometry.running_bond needs exactly one of courses and height; neither is given",
            ))
        }
        (Some(n), _) => n as usize,
        (None, Some(_)) => 0, // from the height
    };
    let openings = match openings {
        Some(o) if !o.is_none() => rects_from(o, "geometry.running_bond.openings")?,
        _ => vec![],
    };
    let p = RunningBond {
        block_length,
        block_height,
        courses,
        height,
        length,
        first_course,
        openings,
    };
    let blocks = guarded(|| geometry::running_bond(&p))?;
    if blocks.is_empty() {
        return Err(InputError::new_err(format!(
            "geometry.running_bond: no block fits in a wall of length {length:e} m (block length {block_length:e} m, height {:?}): no wall to build",
            p.height
        )));
    }
    Ok(rects_to_py(py, &blocks))
}

/// Blocks [x0, y0, x1, y1] (shape (n, 4), m) from courses listed bottom to top; each entry is a
/// length in units of block_length, a negative entry is a gap of that length.
#[pyfunction]
pub(crate) fn pattern<'py>(
    py: Python<'py>,
    block_length: f64,
    block_height: f64,
    rows: Vec<Vec<f64>>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let blocks = guarded(|| geometry::pattern(block_length, block_height, &rows))?;
    if blocks.is_empty() {
        return Err(InputError::new_err(
            "geometry.pattern.rows hold no block (every course is empty or a gap): no wall to build",
        ));
    }
    Ok(rects_to_py(py, &blocks))
}

/// `blocks` [x0, y0, x1, y1] (m) with `openings` cut out as `running_bond` cuts them: a block partly
/// inside an opening becomes its parts outside it, an opening's edge within 5% of `block_length`
/// (across) or `block_height` (up) of a block's edge being moved onto it.
#[pyfunction]
pub(crate) fn cut_openings<'py>(
    py: Python<'py>,
    blocks: &Bound<'py, PyAny>,
    openings: &Bound<'py, PyAny>,
    block_length: f64,
    block_height: f64,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let blocks = rects_from(blocks, "blocks")?;
    let openings = rects_from(openings, "geometry.running_bond.openings")?;
    let snap = [geometry::MIN_PART * block_length, geometry::MIN_PART * block_height];
    let cut = guarded(|| geometry::cut_openings(blocks, &openings, snap, "geometry.running_bond.openings"))?;
    Ok(rects_to_py(py, &cut))
}

/// An arch of voussoirs, as a dict: "blocks" (the voussoirs left to right, then the piers' blocks, each a list of
/// vertices [x, y] counter-clockwise, m), "supports" (the two abutments, left and right; empty on piers), "intrados"
/// and "extrados" (the joints' ends along each, left to right, m). Model(blocks, supports=supports) is the arch.
///
/// kind: "semicircular", "segmental", "pointed" or "elliptical". The intrados springs from y = 0, symmetric about
/// x = 0. span: the intrados's clear span [m], or radius: the centreline's radius [m] (semicircular and segmental
/// only). rise: the intrados's rise [m] (segmental: less than its radius; pointed: at least span / 2; elliptical:
/// the vertical semi-axis). thickness: the ring's, along the joints [m]; voussoirs: their number (even for a pointed
/// arch: a joint at its crown).
/// Joints: radial on circular arcs (a pointed arch's crown joint vertical), normal to the intrados of an elliptical
/// arch (at equal steps of its parametric angle, the extrados the intrados offset by the thickness); the intrados and
/// extrados of each voussoir are straight chords between its joints' ends.
/// Springings: abutments (fixed supports; the default) out to abutment_width [m] from the intrados's springing point
/// (default: the springing joint's extent) and abutment_height [m] below it (default: the thickness); or piers of
/// wall blocks, pier_width [m] wide from the intrados's springing point and pier_height [m] from the ground to it,
/// in pier_courses courses (default 1: a single block), standing on the base.
/// Backfill: backfill_level [m] (its top, above the springing line y = 0) and backfill_density [kg/m3], both or
/// neither: each voussoir carries the fill in the vertical strip over its extrados chord up to the level, its weight
/// (density x wall_thickness x gravity x the strip's area) at the extrados under the strip's centroid, in "carried"
/// (a list of (block, [x, y], weight [N]), empty without a fill: Model(..., carried=made["carried"])). wall_thickness
/// [m] and gravity [m/s2] are the Model's own (defaults those of Model: 1.0 and 9.81), so that the fill's mass is its
/// density times its volume. The fill's weight and mass move with the voussoir under it; its lateral pressure, its
/// strength and the fill over the abutments or piers are not modelled.
#[pyfunction]
#[pyo3(signature = (kind, thickness, voussoirs, span=None, radius=None, rise=None, abutment_width=None, abutment_height=None, pier_width=None, pier_height=None, pier_courses=None, backfill_level=None, backfill_density=None, wall_thickness=None, gravity=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn arch<'py>(
    py: Python<'py>,
    kind: &str,
    thickness: f64,
    voussoirs: i64,
    span: Option<f64>,
    radius: Option<f64>,
    rise: Option<f64>,
    abutment_width: Option<f64>,
    abutment_height: Option<f64>,
    pier_width: Option<f64>,
    pier_height: Option<f64>,
    pier_courses: Option<i64>,
    backfill_level: Option<f64>,
    backfill_density: Option<f64>,
    wall_thickness: Option<f64>,
    gravity: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let mut a = arch_from("geometry.arch", kind, thickness, voussoirs, [span, radius, rise], [abutment_width, abutment_height, pier_width, pier_height], pier_courses)?;
    let density = match (backfill_level, backfill_density) {
        (Some(_), Some(d)) => Some(d),
        (None, None) => None,
        (Some(_), None) => return Err(required("geometry.arch.backfill.density", "a backfill's level")),
        (None, Some(_)) => return Err(required("geometry.arch.backfill.level", "a backfill's density")),
    };
    a.backfill = backfill_level;
    let made = guarded(|| geometry::arch(&a))?;
    let spec = ModelSpec::default();
    let carried = match density {
        Some(d) => guarded(|| made.fill_loads(d, wall_thickness.unwrap_or(spec.thickness), gravity.unwrap_or(spec.gravity)))?,
        None => vec![],
    };
    let d = PyDict::new(py);
    d.set_item("blocks", polygon_lists(&made.blocks))?;
    d.set_item("supports", polygon_lists(&made.supports))?;
    d.set_item("intrados", made.intrados)?;
    d.set_item("extrados", made.extrados)?;
    d.set_item("carried", carried_to_py(&carried))?;
    Ok(d)
}

/// The InputError of `key`, required with `what`.
fn required(key: &str, what: &str) -> PyErr {
    py_error("InputError", format!("{key} is required with {what}"), Some(key.to_string()))
}

/// The arch of the arguments of `arch` (a barrel vault's section too), the lengths [m] given as
/// [span, radius, rise] and [abutment_width, abutment_height, pier_width, pier_height]; `what`
/// names its keys ("geometry.arch").
pub(crate) fn arch_from(
    what: &str,
    kind: &str,
    thickness: f64,
    voussoirs: i64,
    [span, radius, rise]: [Option<f64>; 3],
    [abutment_width, abutment_height, pier_width, pier_height]: [Option<f64>; 4],
    pier_courses: Option<i64>,
) -> PyResult<Arch> {
    let kind: ArchKind = kind.parse().map_err(|e: Error| to_py(e.renamed("geometry.arch", what)))?;
    let voussoirs = count(&format!("{what}.voussoirs"), voussoirs, 1)?;
    let piers = pier_width.is_some() || pier_height.is_some() || pier_courses.is_some();
    let springing = match (piers, pier_width, pier_height) {
        (false, _, _) => Springing::Abutments { width: abutment_width, height: abutment_height },
        _ if abutment_width.is_some() || abutment_height.is_some() => {
            return Err(InputError::new_err(format!("{what}: give abutment_width and abutment_height, or pier_width, pier_height and pier_courses, not both")))
        }
        (true, Some(width), Some(height)) => Springing::Piers {
            width,
            height,
            courses: pier_courses.map_or(Ok(1), |c| count(&format!("{what}.pier_courses"), c, 1))?,
        },
        (true, None, _) => return Err(InputError::new_err(format!("{what}.pier_width is required for piers"))),
        (true, _, None) => return Err(InputError::new_err(format!("{what}.pier_height is required for piers"))),
    };
    Ok(Arch { kind, span, radius, rise, thickness, voussoirs, springing, backfill: None })
}

/// The blocks as lists of vertices [x, y] (m), counter-clockwise.
fn polygon_lists(ps: &[Polygon]) -> Vec<Vec<[f64; 2]>> {
    ps.iter().map(|p| p.vertices().to_vec()).collect()
}

/// The blocks of a gable wall, each a list of vertices [x, y] counter-clockwise (m), course by course bottom to top,
/// left to right: a running bond (block_length x block_height [m], courses alternating half-block and whole-block
/// starts, first_course "half" or "full" for the lowest) from x = 0 to length [m] on y = 0, under a top that rises in
/// a straight line from eaves_height [m] at x = 0 to ridge_height [m] at x = ridge_x [m] (default: length / 2) and
/// falls to eaves_height at x = length; a ridge at 0 or length makes a single slope. The blocks are cut at the rakes
/// (convex polygons); a cut block of less than 25% of a whole block's area is merged with its neighbour towards the
/// ridge, and a course at the ridge lower than 25% of block_height is joined to the course below: nothing is
/// dropped, the blocks tile the gable. Model(blocks) is the wall.
#[pyfunction]
#[pyo3(signature = (block_length, block_height, length, eaves_height, ridge_height, ridge_x=None, first_course=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn gable(
    block_length: f64,
    block_height: f64,
    length: f64,
    eaves_height: f64,
    ridge_height: f64,
    ridge_x: Option<f64>,
    first_course: Option<&str>,
) -> PyResult<Vec<Vec<[f64; 2]>>> {
    let first_course = first_course.map_or(Ok(FirstCourse::default()), Gable::first_course).map_err(to_py)?;
    let p = Gable { block_length, block_height, length, eaves_height, ridge_height, ridge_x, first_course };
    Ok(polygon_lists(&guarded(|| geometry::gable(&p))?))
}

/// The stones of a stone wall, each a list of vertices [x, y] counter-clockwise (m), course by course bottom to top,
/// left to right: a wall from x = 0 to length [m] and from y = 0 to height [m] (a flat base and a flat top), in
/// round(height / stone_height) courses of heights drawn in stone_height (1 +- irregularity) [m], of stones of lengths
/// drawn in stone_length (1 +- irregularity) [m] (irregularity in 0..=0.5). Head joints are inclined from the vertical
/// by angles drawn within +-head_angle (degrees, 0..=30), bed joints from the horizontal within +-bed_angle (degrees,
/// 0..=10; less where a course would be left thinner than half its height at the wall's ends); no stone is shorter than
/// 25% of stone_length along a bed joint, and the head joints of two courses are at least that far apart along the bed
/// joint between them. Every joint is an edge the two stones share. The same seed (an integer in 0..2^64) gives the
/// same wall, bit for bit, on any machine. Model(stones) is the wall.
#[pyfunction]
#[pyo3(signature = (length, height, stone_length, stone_height, irregularity=0.3, head_angle=15.0, bed_angle=0.0, seed=0))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn stone_wall(
    length: f64,
    height: f64,
    stone_length: f64,
    stone_height: f64,
    irregularity: f64,
    head_angle: f64,
    bed_angle: f64,
    seed: i128,
) -> PyResult<Vec<Vec<[f64; 2]>>> {
    let seed = u64::try_from(seed).map_err(|_| {
        InputError::new_err(format!("geometry.stone_wall.seed must be an integer in 0..=18446744073709551615, got {seed}"))
    })?;
    let p = StoneWall { length, height, stone_length, stone_height, irregularity, head_angle, bed_angle, seed };
    Ok(polygon_lists(&guarded(|| geometry::stone_wall(&p))?))
}
