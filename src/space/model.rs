//! [`Model3`]: the 3D model built from a [`ModelSpec3`]: the checks of the input, the base and
//! the top beam, the contacts, masses, supports and loads.

use super::{detect_polyhedra, Box3, Contact, LiveLoad3, ModelSpec3};
use crate::error::{non_negative, positive, Error, Result};
use crate::geometry::MAX_BLOCKS;
use crate::interface::{BlockKind, Family};
use crate::joint::JointLaw;
use crate::model::{CarriedLoad, JointLaws};
use crate::shape::{Polyhedron, Volume};

mod moved;

/// A wall of rigid blocks (boxes, or convex polyhedra) joined by contacts, with its base, top
/// beam, supports and loads. Stateless: solvers read it.
///
/// Dof: 6 per block, `6 i + k` for (ux, uy, uz, rx, ry, rz) of block `i`, small rotations about
/// axes through its centroid; forces are (Fx, Fy, Fz, Mx, My, Mz) about the centroid.
#[derive(Debug, Clone)]
pub struct Model3 {
    boxes: Vec<Box3>,
    shapes: Vec<Polyhedron>,
    /// per block, whether it is a box (its `boxes` entry is the block, not the box around it)
    is_box: Vec<bool>,
    kinds: Vec<BlockKind>,
    n_wall: usize,
    base: Option<usize>,
    top: Option<usize>,
    gravity: f64,
    live: LiveLoad3,
    laws: JointLaws,
    centroids: Vec<[f64; 3]>,
    mass: Vec<f64>,
    inertia: Vec<[f64; 3]>,
    products: Vec<(usize, [f64; 3])>,
    carried: Vec<CarriedLoad<3>>,
    tensor: Vec<[[f64; 3]; 3]>,
    contacts: Vec<Contact>,
    fixed: Vec<bool>,
    f_dead: Vec<f64>,
    f_live: Vec<f64>,
}

impl Model3 {
    /// Builds and checks a model; the error names the field or block at fault (two overlapping
    /// blocks are both named).
    pub fn new(spec: &ModelSpec3) -> Result<Model3> {
        Model3::new_with(spec, &mut || true)
    }

    /// [`Model3::new`], calling `poll` every few thousand blocks of the search for contacts:
    /// `false` stops it with [`Error::Interrupted`].
    pub fn new_with(spec: &ModelSpec3, poll: &mut dyn FnMut() -> bool) -> Result<Model3> {
        check_spec(spec)?;
        let (shapes, is_box, kinds, base, top) = frame(spec);
        let boxes: Vec<Box3> = shapes
            .iter()
            .map(|p| {
                let b = p.aabb();
                Box3 { min: b.min, max: b.max }
            })
            .collect();
        let n_wall = spec.blocks.len() + spec.polyhedra.len();
        let name = |i: usize| block_name(i, n_wall, base, top, &boxes, &shapes, &is_box);
        let contacts = detect_polyhedra(&shapes, &kinds, name, poll)?;
        let held = kinds.contains(&BlockKind::Base);
        check_touched(&contacts, shapes.len(), n_wall, held, top, name)?;
        // a box's closed forms (the polyhedron's to rounding), else the polyhedron's
        let props: Vec<Volume> = shapes
            .iter()
            .zip(&boxes)
            .zip(&is_box)
            .map(|((p, b), &boxed)| if boxed { box_volume(b) } else { p.volume_properties() })
            .collect();
        let mut mass: Vec<f64> = props.iter().map(|v| spec.density * v.volume).collect();
        let mut tensor: Vec<[[f64; 3]; 3]> = props.iter().map(|v| v.inertia.map(|r| r.map(|x| spec.density * x))).collect();
        let mut centroids: Vec<[f64; 3]> = props.iter().map(|v| v.centroid).collect();
        let products = carry(spec, &shapes, &mut mass, &mut tensor, &mut centroids, name)?;
        let inertia: Vec<[f64; 3]> = tensor.iter().map(|t| [t[0][0], t[1][1], t[2][2]]).collect();
        for (i, (&m, j)) in mass.iter().zip(&inertia).enumerate() {
            if !(m.is_finite() && m > 0.0 && j.iter().all(|&v| v.is_finite() && v > 0.0)) {
                return Err(Error::input(format!(
                    "{}: its mass ({m:e} kg) or rotary inertia ({:e}, {:e}, {:e} kg m2) is zero or not finite: check density and the block's size",
                    name(i), j[0], j[1], j[2]
                )));
            }
            if !(m * spec.gravity).is_finite() {
                return Err(Error::input(format!(
                    "{}: its weight (mass {m:e} kg times gravity = {} m/s2) is not finite",
                    name(i),
                    spec.gravity
                )));
            }
        }
        let weight: f64 = (0..n_wall).chain(top).map(|i| mass[i] * spec.gravity).sum();
        crate::error::check_weight(weight, spec.density, spec.gravity)?;
        let nb = boxes.len();
        let mut model = Model3 {
            boxes,
            shapes,
            is_box,
            kinds,
            n_wall,
            base,
            top,
            gravity: spec.gravity,
            live: spec.live,
            laws: spec.joints,
            centroids,
            mass,
            inertia,
            products,
            carried: spec.carried.clone(),
            tensor,
            contacts,
            fixed: vec![false; 6 * nb],
            f_dead: vec![0.0; 6 * nb],
            f_live: vec![0.0; 6 * nb],
        };
        model.supports_and_loads();
        model.check_scales()?;
        Ok(model)
    }

    /// Refuses numbers each valid alone whose scales together leave the solvers nothing to
    /// resolve, as the plane's model does: contact stiffnesses that overflow, and joints so soft
    /// (or loads so heavy) that the dead loads alone would sink the wall into its base joints by
    /// more than [`crate::model::SETTLEMENT_LIMIT`] of its size, out of the small-displacement
    /// model (the explicit solver then found no equilibrium under them).
    fn check_scales(&self) -> Result<()> {
        for (k, c) in self.contacts.iter().enumerate() {
            let law = self.law(k);
            if !(law.normal_stiffness * c.area).is_finite() || !(law.shear_stiffness * c.area).is_finite() {
                return Err(Error::input(format!(
                    "the contact of {} and {}: its stiffness ({}.normal_stiffness or shear_stiffness times its area, {:e} m2) is not finite: check the joints' stiffness",
                    self.block_name(c.a),
                    self.block_name(c.b),
                    crate::model::law_key(&self.laws, c.family),
                    c.area
                )));
            }
        }
        // the dead loads are carried to the base through its contacts: their settlement
        let vertical: f64 = self.f_dead.iter().skip(2).step_by(6).sum::<f64>().abs();
        crate::model::check_settlement(vertical, self.base_stiffness(), self.size(), "gravity, density and the joints' normal_stiffness")
    }

    /// The normal stiffness of the base's contacts together \[N/m\]: the wall's vertical stiffness
    /// as one body on its base (0 without a base).
    pub(crate) fn base_stiffness(&self) -> f64 {
        self.contacts.iter().enumerate().filter(|(_, c)| c.family == Family::Base).map(|(k, c)| self.law(k).normal_stiffness * c.area).sum()
    }

    /// The base's fixed dofs, the weights of the wall and the top beam, and the live load on
    /// the same blocks (the beam weighs in 3D: its weight is loaded like the wall's).
    fn supports_and_loads(&mut self) {
        for (i, &kind) in self.kinds.iter().enumerate() {
            if kind == BlockKind::Base {
                self.fixed[6 * i..6 * i + 6].fill(true);
            }
        }
        let free = (0..self.n_wall).chain(self.top);
        for i in free {
            self.f_dead[6 * i + 2] = -self.mass[i] * self.gravity;
        }
        if let LiveLoad3::HorizontalWeight { direction } = self.live {
            let (c, s) = cos_sin_deg(direction);
            for i in (0..self.n_wall).chain(self.top) {
                let w = self.mass[i] * self.gravity;
                self.f_live[6 * i] = w * c;
                self.f_live[6 * i + 1] = w * s;
            }
        }
    }

    /// Number of blocks, the base and the top beam included.
    pub fn n_blocks(&self) -> usize {
        self.boxes.len()
    }
    /// Number of wall blocks (the user's, first: `0..n_wall`).
    pub fn n_wall(&self) -> usize {
        self.n_wall
    }
    /// Every block's box: wall blocks, then the base, then the top beam, then the supports; a
    /// box is itself, a polyhedron the box around it.
    pub fn boxes(&self) -> &[Box3] {
        &self.boxes
    }
    /// Every block's shape, a convex polyhedron, in the order of [`Model3::boxes`].
    pub fn shapes(&self) -> &[Polyhedron] {
        &self.shapes
    }
    /// What each block is (wall, base or support, top beam).
    pub fn kinds(&self) -> &[BlockKind] {
        &self.kinds
    }
    /// The index of the base, if any.
    pub fn base(&self) -> Option<usize> {
        self.base
    }
    /// The index of the top beam, if any.
    pub fn top(&self) -> Option<usize> {
        self.top
    }
    /// A label for messages: "block 7 [x0, y0, z0, x1, y1, z1]" (a box), "block 7 (polyhedron
    /// of 6 vertices: ...)", "the base", "the top beam" or "support 0 (polyhedron ...)".
    pub fn block_name(&self, i: usize) -> String {
        block_name(i, self.n_wall, self.base, self.top, &self.boxes, &self.shapes, &self.is_box)
    }
    /// Each block's centroid \[m\] (where its dofs are and its moments are taken).
    pub fn centroids(&self) -> &[[f64; 3]] {
        &self.centroids
    }
    /// Mass of each block \[kg\] (the base's too, though it is fixed).
    pub fn mass(&self) -> &[f64] {
        &self.mass
    }
    /// Each block's moments of inertia about axes through its centroid along x, y and z, the
    /// diagonal of [`Model3::inertia_tensor`] (a box's principal moments, `m (b^2 + c^2) / 12`,
    /// ... for sides a, b, c) \[kg m2\].
    pub fn inertia(&self) -> &[[f64; 3]] {
        &self.inertia
    }
    /// Each block's inertia tensor about its centroid in global axes \[kg m2\] (diagonal for a
    /// box).
    pub fn inertia_tensor(&self) -> &[[[f64; 3]; 3]] {
        &self.tensor
    }
    /// The products of inertia `[yz, xz, xy]` (off the diagonal of [`Model3::inertia_tensor`])
    /// that the loads carried by block `i` give it \[kg m2\] (zeros for a block without loads).
    pub fn carried_products(&self, i: usize) -> [f64; 3] {
        self.products.iter().find(|p| p.0 == i).map_or([0.0; 3], |p| p.1)
    }
    /// The loads carried by wall blocks, as given (their masses are in [`Model3::mass`] and
    /// [`Model3::inertia`]).
    pub fn carried(&self) -> &[CarriedLoad<3>] {
        &self.carried
    }
    /// The contacts, sorted by their blocks (a, b).
    pub fn contacts(&self) -> &[Contact] {
        &self.contacts
    }
    /// The joint law of contact `k` (its family's).
    pub fn law(&self, k: usize) -> &JointLaw {
        self.laws.of(self.contacts[k].family)
    }
    /// The joint laws of the families.
    pub fn laws(&self) -> &JointLaws {
        &self.laws
    }
    /// Refuses, for `what` (an analysis that raises lambda, the live load's multiplier), a model
    /// without a live load: it has nothing to raise (a pushover of zero loads would take every
    /// level it may before it gave up).
    pub fn check_live(&self, what: &str) -> Result<()> {
        if self.live == LiveLoad3::None {
            return Err(Error::input_at(
                "live",
                format!("live = \"none\": {what} raises lambda, the multiplier of the live load, and this model has none (live = \"horizontal_weight\", the default, pushes each block by lambda times its weight)"),
            ));
        }
        Ok(())
    }
    /// Refuses a wall that nothing holds: no base (so no fixed block), or blocks that no chain of
    /// contacts joins to the base (limit analysis would not converge on it, and the explicit
    /// solver would see the wall fall under its weight).
    pub fn check_supports(&self) -> Result<()> {
        let nb = self.n_blocks();
        let held: Vec<bool> = (0..nb).map(|i| self.fixed[6 * i..6 * i + 6].iter().any(|&f| f)).collect();
        if !held.iter().any(|&s| s) {
            return Err(Error::input(NO_SUPPORT));
        }
        let loose = crate::model::unsupported(held, self.contacts.iter().map(|c| (c.a, c.b)));
        if let Some(&first) = loose.first() {
            return Err(Error::input(format!(
                "{} block{} not joined to the base by any chain of contacts, {} first: nothing carries {}",
                loose.len(),
                if loose.len() == 1 { " is" } else { "s are" },
                self.block_name(first),
                if loose.len() == 1 { "it" } else { "them" },
            )));
        }
        Ok(())
    }
    /// Fixed dof flags, 6 per block (ux, uy, uz, rx, ry, rz): the base's all true.
    pub fn fixed(&self) -> &[bool] {
        &self.fixed
    }
    /// Dead loads, 6 per block (Fx, Fy, Fz \[N\], Mx, My, Mz \[N m\] about the centroid): the weight
    /// `-m g` along z on the wall blocks and the top beam (none on the base). No moments: the
    /// weight acts at the centroid.
    pub fn dead_load(&self) -> &[f64] {
        &self.f_dead
    }
    /// The live load for lambda = 1, 6 per block as [`Model3::dead_load`]: for
    /// [`LiveLoad3::HorizontalWeight`], `m g (cos d, sin d, 0)` on each block that weighs (the
    /// wall's and the top beam; none on the base), no moments; all zero for [`LiveLoad3::None`].
    pub fn live_load(&self) -> &[f64] {
        &self.f_live
    }
    /// The size of the model \[m\]: the largest side of the box around every block (base and
    /// top beam included).
    pub fn size(&self) -> f64 {
        size(&self.boxes)
    }
    /// Acceleration of gravity \[m/s2\].
    pub fn gravity(&self) -> f64 {
        self.gravity
    }
    /// The live load.
    pub fn live(&self) -> LiveLoad3 {
        self.live
    }
    /// The live load's direction in plan, a unit vector (x, y) (+x without a live load).
    pub(crate) fn horizontal(&self) -> [f64; 2] {
        match self.live {
            LiveLoad3::HorizontalWeight { direction } => {
                let (c, s) = cos_sin_deg(direction);
                [c, s]
            }
            LiveLoad3::None => [1.0, 0.0],
        }
    }
    /// The same model with the live load lambda times the weights, along gravity (lambda a
    /// factor on the self-weight), as the plane's
    /// [`Model::with_live_along_gravity`](crate::model::Model::with_live_along_gravity): with
    /// dry joints limit analysis of it is unbounded if the blocks stand under their own weight
    /// and finds no equilibrium if not.
    pub fn with_live_along_gravity(&self) -> Model3 {
        let mut m = self.clone();
        m.f_live.fill(0.0);
        for (d, &f) in self.f_dead.iter().enumerate().skip(2).step_by(6) {
            m.f_live[d] = f;
        }
        m
    }
    /// The indices of the contacts of block `i` (a linear scan: for tests and reports, not for
    /// solvers' inner loops).
    pub fn contacts_of(&self, i: usize) -> Vec<usize> {
        (0..self.contacts.len()).filter(|&k| self.contacts[k].a == i || self.contacts[k].b == i).collect()
    }
}

/// The carried loads of `spec`, checked (each on a wall block, inside its box within the contact
/// tolerance) and lumped: their masses into `mass`, each loaded block's `centroid` moved to its
/// centre of mass and its `inertia` about x, y and z given the parallel-axis terms
/// `trace S - S_kk`. Returns the loaded blocks' products of inertia `-S_yz, -S_xz, -S_xy`.
fn carry(
    spec: &ModelSpec3,
    shapes: &[Polyhedron],
    mass: &mut [f64],
    tensor: &mut [[[f64; 3]; 3]],
    centroids: &mut [[f64; 3]],
    name: impl Fn(usize) -> String,
) -> Result<Vec<(usize, [f64; 3])>> {
    let boxes: Vec<Box3> = shapes.iter().map(|p| Box3 { min: p.aabb().min, max: p.aabb().max }).collect();
    let size = size(&boxes);
    // how far a point lies outside block i: the largest of its distances beyond the faces' planes
    let outside = |i: usize, p: [f64; 3]| {
        shapes[i].faces().iter().map(|f| (0..3).map(|k| f.normal[k] * p[k]).sum::<f64>() - f.offset).fold(f64::MIN, f64::max)
    };
    crate::model::check_carried_inside(&spec.carried, crate::shape::contact_tolerance(size), outside, name)?;
    let lumped = crate::model::lump_carried(&spec.carried, spec.gravity, mass, centroids);
    Ok(lumped
        .into_iter()
        .map(|(i, s)| {
            // the point masses' tensor about the new centre: trace(S) I - S
            let trace = s[0][0] + s[1][1] + s[2][2];
            for a in 0..3 {
                for b in 0..3 {
                    tensor[i][a][b] += if a == b { trace } else { 0.0 } - s[a][b];
                }
            }
            (i, [-s[1][2], -s[0][2], -s[0][1]])
        })
        .collect())
}

/// The largest side of the box around `boxes` \[m\].
fn size(boxes: &[Box3]) -> f64 {
    let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
    for b in boxes {
        for k in 0..3 {
            lo[k] = lo[k].min(b.min[k]);
            hi[k] = hi[k].max(b.max[k]);
        }
    }
    (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max)
}

/// cos and sin of `deg` degrees, exact at multiples of 90 (a load at 90 deg has no x part).
fn cos_sin_deg(deg: f64) -> (f64, f64) {
    let r = deg.rem_euclid(360.0);
    match r {
        0.0 => (1.0, 0.0),
        90.0 => (0.0, 1.0),
        180.0 => (-1.0, 0.0),
        270.0 => (0.0, -1.0),
        _ => {
            let (s, c) = r.to_radians().sin_cos();
            (c, s)
        }
    }
}

/// The checks of the spec's numbers, blocks and laws, each alone, before anything is built.
fn check_spec(spec: &ModelSpec3) -> Result<()> {
    positive("density", spec.density)?;
    non_negative("gravity", spec.gravity)?;
    crate::model::check_carried(&spec.carried, spec.blocks.len() + spec.polyhedra.len(), spec.gravity)?;
    if let Some(h) = spec.top {
        positive("top", h)?;
    }
    let n = spec.blocks.len() + spec.polyhedra.len();
    if n == 0 {
        return Err(Error::input("blocks: the wall has no blocks"));
    }
    if n + spec.supports.len() > MAX_BLOCKS {
        return Err(crate::geometry::too_many_blocks("blocks", (n + spec.supports.len()) as f64));
    }
    crate::error::check_memory(&format!("a model of {n} blocks"), n as f64 * crate::error::MODEL_BYTES_PER_BLOCK)?;
    for (i, b) in spec.blocks.iter().enumerate() {
        b.validate(&format!("block {i}"))?;
    }
    spec.joints.default.validate("joints")?;
    let j = &spec.joints;
    for (f, law) in [(Family::Bed, j.bed), (Family::Head, j.head), (Family::Base, j.base), (Family::Top, j.top)] {
        if let Some(l) = law {
            l.validate(&format!("joints.{}", f.name()))?;
        }
    }
    if let LiveLoad3::HorizontalWeight { direction } = spec.live {
        if !direction.is_finite() {
            return Err(Error::input_at("live.direction", format!("live.direction must be finite, got {direction}")));
        }
        if spec.gravity == 0.0 {
            return Err(Error::input_at(
                "live",
                "the horizontal-weight live load needs gravity > 0 (it is lambda times the weights)",
            ));
        }
    }
    Ok(())
}

/// The volume properties of a box: its closed forms (the polyhedron's, to rounding).
fn box_volume(b: &Box3) -> Volume {
    let sq = b.size().map(|s| s * s);
    let v = b.volume();
    let diag = |d: [f64; 3]| std::array::from_fn(|i| std::array::from_fn(|j| if i == j { d[i] } else { 0.0 }));
    let [x, y, z] = sq;
    Volume {
        volume: v,
        centroid: b.centroid(),
        second: diag(sq.map(|s| v * s / 12.0)),
        inertia: diag([v * (y + z) / 12.0, v * (x + z) / 12.0, v * (x + y) / 12.0]),
    }
}

/// The wall's blocks as polyhedra (the boxes first), with the base under them and the top beam
/// over them (each over the box around the wall in plan; the base as deep as the tallest block,
/// as in 2D), then the supports; whether each is a box, and what it is.
#[allow(clippy::type_complexity)]
fn frame(spec: &ModelSpec3) -> (Vec<Polyhedron>, Vec<bool>, Vec<BlockKind>, Option<usize>, Option<usize>) {
    let mut shapes: Vec<Polyhedron> = spec.blocks.iter().map(Box3::polyhedron).chain(spec.polyhedra.iter().cloned()).collect();
    let mut is_box: Vec<bool> = (0..shapes.len()).map(|i| i < spec.blocks.len()).collect();
    let (mut lo, mut hi, mut hmax) = ([f64::MAX; 3], [f64::MIN; 3], 0.0f64);
    for p in &shapes {
        let b = p.aabb();
        for k in 0..3 {
            lo[k] = lo[k].min(b.min[k]);
            hi[k] = hi[k].max(b.max[k]);
        }
        hmax = hmax.max(b.max[2] - b.min[2]);
    }
    let mut kinds = vec![BlockKind::Wall; shapes.len()];
    let mut add = |p: Polyhedron, kind: BlockKind, boxed: bool| {
        shapes.push(p);
        kinds.push(kind);
        is_box.push(boxed);
        shapes.len() - 1
    };
    let base = spec.base.then(|| add(Box3::new(lo[0], lo[1], lo[2] - hmax, hi[0], hi[1], lo[2]).polyhedron(), BlockKind::Base, true));
    let top = spec.top.map(|h| add(Box3::new(lo[0], lo[1], hi[2], hi[0], hi[1], hi[2] + h).polyhedron(), BlockKind::Top, true));
    for s in &spec.supports {
        add(s.clone(), BlockKind::Base, false);
    }
    (shapes, is_box, kinds, base, top)
}

/// The refusal of a wall without a base: nothing holds it.
const NO_SUPPORT: &str =
    "the wall has no support: no base ([base] kind = \"none\", base=False): nothing carries its weight";

/// Refuses a wall block, or the top beam, that no contact reaches; without a base or a support
/// (`held` false), the wall itself (a lone block touches nothing because nothing holds it: the
/// support is what is missing).
fn check_touched(
    contacts: &[Contact],
    nb: usize,
    n_wall: usize,
    held: bool,
    top: Option<usize>,
    name: impl Fn(usize) -> String,
) -> Result<()> {
    let mut touched = vec![false; nb];
    for c in contacts {
        touched[c.a] = true;
        touched[c.b] = true;
    }
    if let Some(i) = (0..n_wall).chain(top).find(|&i| !touched[i]) {
        if !held {
            return Err(Error::input(NO_SUPPORT));
        }
        return Err(Error::input(format!("{} touches no other block", name(i))));
    }
    Ok(())
}

fn block_name(
    i: usize,
    n_wall: usize,
    base: Option<usize>,
    top: Option<usize>,
    boxes: &[Box3],
    shapes: &[Polyhedron],
    is_box: &[bool],
) -> String {
    let label = if is_box[i] { boxes[i].label() } else { shapes[i].label() };
    if Some(i) == base {
        "the base".into()
    } else if Some(i) == top {
        "the top beam".into()
    } else if i < n_wall {
        format!("block {i} {label}")
    } else {
        let first = n_wall + usize::from(base.is_some()) + usize::from(top.is_some());
        format!("support {} {label}", i - first)
    }
}
