//! The model: blocks, interfaces, joint laws, supports and loads.
//!
//! A block is a convex polygon ([`Polygon`]): the model holds the polygons with what the shape
//! layer ([`crate::shape`]) says of them (area, centroid, polar moment, contacts) and gives the
//! solvers masses, inertias, centroids, interfaces and loads, never a shape. A rectangle is a
//! polygon of four vertices.
//!
//! Block numbering: wall blocks `0..n_wall` in the order given, then the supports (fixed blocks,
//! in the order given), then the base (if any), then the top beam (if any). Each block has 3 dof
//! at its centroid (its centre of mass: the polygon's, moved by the loads it carries, if any):
//! u1, u2 \[m\], phi \[rad\]; the global dof index of dof k of block i is `3 i + k`.
//!
//! ```
//! use masonry_dem::geometry::Rect;
//! use masonry_dem::model::{Model, ModelSpec};
//! use masonry_dem::shape::Polygon;
//! let spec = ModelSpec { blocks: vec![Rect::new(0.0, 0.0, 0.4, 0.175).into()], ..ModelSpec::default() };
//! let model = Model::new(spec).unwrap();
//! assert_eq!(model.n_wall(), 1);
//! assert_eq!(model.interfaces().len(), 1); // the block on the base
//! // a triangular block on an inclined support, no base: the support carries it
//! let spec = ModelSpec {
//!     blocks: vec![Polygon::new(vec![[0.0, 0.0], [1.0, 0.5], [0.0, 1.0]])],
//!     supports: vec![Polygon::new(vec![[0.0, -1.0], [1.0, -1.0], [1.0, 0.5], [0.0, 0.0]])],
//!     base: false,
//!     ..ModelSpec::default()
//! };
//! let model = Model::new(spec).unwrap();
//! assert_eq!((model.n_blocks(), model.interfaces().len()), (2, 1));
//! assert!((model.centroids()[0][0] - 1.0 / 3.0).abs() < 1e-15);
//! ```

mod build;
mod carried;
mod keys;
mod moved;
mod movement;
mod supports;

pub(crate) use build::{check_settlement, law_key};
pub use carried::CarriedLoad;
pub use movement::{Direction, SupportMovement};
pub(crate) use carried::{check as check_carried, check_inside as check_carried_inside, lump as lump_carried};
pub(crate) use supports::unsupported;

use crate::geometry::Rect;
use crate::interface::{BlockKind, Family, Interface};
use crate::joint::{JointLaw, Kinds, Section};
use crate::shape::{Aabb, Polygon};

/// The joint law of each family; a family without its own law uses `default`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct JointLaws {
    /// The law of every family without its own.
    pub default: JointLaw,
    /// Joints between wall blocks within 45 degrees of the horizontal (horizontal joints between
    /// rectangles).
    pub bed: Option<JointLaw>,
    /// Joints between wall blocks steeper than 45 degrees (vertical joints between rectangles).
    pub head: Option<JointLaw>,
    /// Joints between the wall and its base or its supports.
    pub base: Option<JointLaw>,
    /// Joints between the wall and the top beam.
    pub top: Option<JointLaw>,
}

impl JointLaws {
    /// One law for every interface.
    pub fn uniform(law: JointLaw) -> Self {
        JointLaws {
            default: law,
            ..Default::default()
        }
    }
    /// The law of a family.
    pub fn of(&self, f: Family) -> &JointLaw {
        let o = match f {
            Family::Bed => &self.bed,
            Family::Head => &self.head,
            Family::Base => &self.base,
            Family::Top => &self.top,
        };
        o.as_ref().unwrap_or(&self.default)
    }
    /// The family's own law (`None`: it uses `default`).
    pub fn family_mut(&mut self, f: Family) -> &mut Option<JointLaw> {
        match f {
            Family::Bed => &mut self.bed,
            Family::Head => &mut self.head,
            Family::Base => &mut self.base,
            Family::Top => &mut self.top,
        }
    }
}

/// The live load pattern scaled by the load multiplier lambda.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LiveLoad {
    /// A horizontal force lambda * W_i on every wall block, towards +x (lambda dimensionless):
    /// along gravity turned by +90 degrees ([`ModelSpec::gravity_direction`]).
    HorizontalWeight,
    /// A horizontal force of lambda newtons on the top beam, towards +x (as
    /// `HorizontalWeight`'s direction).
    TopHorizontal,
}

/// The rigid top beam resting on the highest blocks.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TopBeam {
    /// Whether the beam's rotation is fixed (kept horizontal).
    pub rotation_fixed: bool,
    /// Dead force [Fx, Fy] on the beam \[N\].
    pub force: [f64; 2],
    /// Whether the beam's vertical position is held once the dead loads are on (the vertical
    /// force on it is then a reaction that changes with the live load); false: the vertical
    /// force stays `force[1]` and the beam is free to rise.
    pub vertical_held: bool,
}

/// Everything needed to build a [`Model`]. SI units.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelSpec {
    /// Wall blocks: convex polygons, either orientation (a rectangle is
    /// `Polygon::from(Rect)`; see [`Polygon::checked`] for what is refused).
    pub blocks: Vec<Polygon>,
    /// Fixed blocks (abutments, springers, an inclined plane): convex polygons whose three dofs
    /// are fixed, with no weight. Their joints with the wall are of the `base` family.
    pub supports: Vec<Polygon>,
    /// Out-of-plane thickness s \[m\].
    pub thickness: f64,
    /// Density [kg/m3].
    pub density: f64,
    /// A fixed rigid foundation under the lowest blocks, spanning the wall (a rectangle under the
    /// box around the wall blocks, as deep as the highest block's box): the blocks whose bottom
    /// edge lies on the box's bottom stand on it.
    pub base: bool,
    /// A rigid top beam resting on the highest blocks, or none.
    pub top: Option<TopBeam>,
    /// The joint law of each family.
    pub joints: JointLaws,
    /// [m/s2]
    pub gravity: f64,
    /// The direction of gravity, a vector of any length (made a unit vector), (0, -1) by
    /// default. It says which way is up (which block of an interface is below, and whether a
    /// joint is a bed or a head joint) and the direction of the horizontal live load (gravity
    /// turned by +90 degrees: +x by default). A wall turned with its gravity gives the same
    /// multipliers. The base and the top beam stay horizontal: give a turned wall supports. The
    /// incremental solvers' curves still follow the control block's displacement along x, and
    /// a time history under a ground motion (along x and y) takes gravity along -y only.
    pub gravity_direction: [f64; 2],
    /// The live load, scaled by lambda.
    pub live: LiveLoad,
    /// Loads carried by wall blocks (a floor's reaction at a point of a block), with their
    /// masses: each loaded block's centre of mass, where its dofs are, is that of the block and
    /// its loads together (see [`CarriedLoad`]).
    pub carried: Vec<CarriedLoad>,
}

impl Default for ModelSpec {
    fn default() -> Self {
        ModelSpec {
            blocks: vec![],
            supports: vec![],
            thickness: 1.0,
            density: 1000.0,
            base: true,
            top: None,
            joints: JointLaws::default(),
            gravity: 9.81,
            gravity_direction: [0.0, -1.0],
            live: LiveLoad::HorizontalWeight,
            carried: vec![],
        }
    }
}

/// The largest settlement of the wall into its base joints under the dead loads, as a fraction
/// of the wall's size, that a model may have (the solvers' small-displacement limit is 0.1).
pub const SETTLEMENT_LIMIT: f64 = 0.01;

/// The largest cohesion or tensile strength, as a multiple of the mean vertical stress of the
/// wall's weight at its base, that a model with the horizontal-weight live load may have: no
/// joint this strong can fail at a multiplier within the solvers' range (1e3 the load scale).
pub const STRENGTH_RANGE: f64 = 1e6;

/// A wall of rigid blocks joined by interfaces, with supports and loads.
#[derive(Debug, Clone)]
pub struct Model {
    polygons: Vec<Polygon>,
    centroids: Vec<[f64; 2]>,
    kinds: Vec<BlockKind>,
    n_wall: usize,
    n_supports: usize,
    base: Option<usize>,
    top: Option<usize>,
    thickness: f64,
    gravity: f64,
    gravity_direction: [f64; 2],
    live: LiveLoad,
    laws: JointLaws,
    mass: Vec<f64>,
    inertia: Vec<f64>,
    weight: Vec<f64>,
    interfaces: Vec<Interface>,
    sections: Vec<Section>,
    fixed: Vec<bool>,
    prescribed: Vec<f64>,
    f_dead: Vec<f64>,
    f_live: Vec<f64>,
    held: Vec<usize>,
    carried: Vec<CarriedLoad>,
}

impl Model {
    /// A label for messages: "block 7 [x0, y0, x1, y1]" (a rectangle), "block 7 (polygon of 5
    /// vertices: ...)", "support 0 ...", "the base" or "the top beam".
    pub fn block_name(&self, i: usize) -> String {
        build::block_name(i, self.n_wall, self.n_supports, self.base, self.top, &self.polygons)
    }

    /// Number of wall blocks (the supports, the base and the top beam not counted).
    pub fn n_wall(&self) -> usize {
        self.n_wall
    }
    /// All blocks: wall blocks, then supports, then base, then top beam.
    pub fn n_blocks(&self) -> usize {
        self.polygons.len()
    }
    /// Every block's polygon (counter-clockwise from its lowest vertex): wall blocks, then the
    /// supports, then the base, then the top beam.
    pub fn polygons(&self) -> &[Polygon] {
        &self.polygons
    }
    /// Every block's centroid \[m\], where its dofs are: its centre of mass (the polygon's
    /// centroid, moved towards the loads it carries if it carries any).
    pub fn centroids(&self) -> &[[f64; 2]] {
        &self.centroids
    }
    /// Every block's bounding box, as a rectangle (a rectangle's is itself).
    pub fn rects(&self) -> Vec<Rect> {
        self.polygons
            .iter()
            .map(|p| {
                let b = p.aabb();
                Rect::new(b.min[0], b.min[1], b.max[0], b.max[1])
            })
            .collect()
    }
    /// The indices of the supports (fixed blocks given by the user).
    pub fn supports(&self) -> std::ops::Range<usize> {
        self.n_wall..self.n_wall + self.n_supports
    }
    /// The size of the model \[m\]: the larger side of the box around every block (supports, base
    /// and top beam included). It does not depend on where the wall stands.
    pub fn size(&self) -> f64 {
        self.polygons.iter().fold(Aabb::around(&[]), |b, p| b.union(&p.aabb())).size()
    }
    /// What each block is (wall, support, base, top beam).
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
    /// Out-of-plane thickness \[m\].
    pub fn thickness(&self) -> f64 {
        self.thickness
    }
    /// Acceleration of gravity \[m/s2\].
    pub fn gravity(&self) -> f64 {
        self.gravity
    }
    /// The direction of gravity (a unit vector; (0, -1) unless given).
    pub fn gravity_direction(&self) -> [f64; 2] {
        self.gravity_direction
    }
    /// The direction of the horizontal live loads: gravity turned by +90 degrees ((1, 0) unless
    /// gravity is turned).
    pub fn horizontal(&self) -> [f64; 2] {
        [-self.gravity_direction[1], self.gravity_direction[0]]
    }
    /// The live load.
    pub fn live(&self) -> LiveLoad {
        self.live
    }
    /// Mass of each block \[kg\], with the masses of the loads it carries.
    pub fn mass(&self) -> &[f64] {
        &self.mass
    }
    /// Rotary inertia of each block about its centroid [kg m2], with the loads it carries as
    /// point masses.
    pub fn inertia(&self) -> &[f64] {
        &self.inertia
    }
    /// The loads carried by wall blocks, as given (their masses are in [`Model::mass`] and
    /// [`Model::inertia`], their weights in [`Model::weight`]).
    pub fn carried(&self) -> &[CarriedLoad] {
        &self.carried
    }
    /// Weight of each block \[N\], with the loads it carries (0 for the supports, the base and
    /// the top beam).
    pub fn weight(&self) -> &[f64] {
        &self.weight
    }
    /// The interfaces, sorted by their blocks (a, b).
    pub fn interfaces(&self) -> &[Interface] {
        &self.interfaces
    }
    /// Each interface's cross-section (length times thickness).
    pub fn sections(&self) -> &[Section] {
        &self.sections
    }
    /// The joint law of interface `k`.
    pub fn law(&self, k: usize) -> &JointLaw {
        self.laws.of(self.interfaces[k].family)
    }
    /// The kinds of the interfaces (the distinct pairs of law and section, at most
    /// [`Kinds::MAX`] in the table), each with the return mapping's constants.
    pub(crate) fn joint_kinds(&self) -> Kinds {
        Kinds::new(self.interfaces.iter().zip(&self.sections).map(|(it, s)| (it.family as u8, self.laws.of(it.family), s)), Kinds::MAX)
    }
    /// Whether some interface's law has cohesion or tensile strength.
    pub fn laws_are_strong(&self) -> bool {
        (0..self.interfaces.len()).any(|k| self.law(k).is_strong())
    }
    /// The joint laws of the families.
    pub fn laws(&self) -> &JointLaws {
        &self.laws
    }
    /// Fixed dof flags (3 per block).
    pub fn fixed(&self) -> &[bool] {
        &self.fixed
    }
    /// Values of the fixed dof (3 per block; 0 where free).
    pub fn prescribed(&self) -> &[f64] {
        &self.prescribed
    }
    /// Dead loads (3 per block: Fx, Fy \[N\], moment [N m]).
    pub fn dead_load(&self) -> &[f64] {
        &self.f_dead
    }
    /// Live load pattern for lambda = 1 (3 per block).
    pub fn live_load(&self) -> &[f64] {
        &self.f_live
    }

    /// The same model with the live load reversed (a wall pushed towards -x as a problem of
    /// its own, for limit analysis).
    pub fn with_live_reversed(&self) -> Model {
        let mut m = self.clone();
        m.f_live.iter_mut().for_each(|f| *f = -*f);
        m
    }

    /// The same model with the live load lambda times the wall blocks' weights, along gravity:
    /// lambda a factor on the self-weight (lambda = 0 the dead state, -1 no load at all). With dry
    /// joints an equilibrium scales with its loads, so limit analysis of it says whether the wall
    /// stands under its own weight: [`Status::Unbounded`](crate::results::Status::Unbounded)
    /// (every multiple of the weight is carried) if it does, and
    /// [`Status::NoEquilibrium`](crate::results::Status::NoEquilibrium) (lambda = -1, the
    /// weight carried by nothing) if not. Near the least thickness of an arch that question is
    /// better posed than the sign of the horizontal multiplier, whose program is infeasible, by
    /// a hair, just below it (where the interior point may stall instead of proving it).
    pub fn with_live_along_gravity(&self) -> Model {
        let mut m = self.clone();
        let g = self.gravity_direction;
        m.f_live.fill(0.0);
        for i in 0..self.n_wall {
            m.f_live[3 * i] = self.weight[i] * g[0];
            m.f_live[3 * i + 1] = self.weight[i] * g[1];
        }
        m
    }

    /// The default control block: the top beam if there is one, else the highest wall block at
    /// the right end (the highest top, then the rightmost right end: largest y1, then largest
    /// x1 for rectangles; up and right as gravity and the live load point).
    pub fn default_control_block(&self) -> usize {
        if let Some(t) = self.top {
            return t;
        }
        let (up, right) = ([-self.gravity_direction[0], -self.gravity_direction[1]], self.horizontal());
        let reach = |i: usize, d: [f64; 2]| {
            self.polygons[i].vertices().iter().map(|v| v[0] * d[0] + v[1] * d[1]).fold(f64::MIN, f64::max)
        };
        (0..self.n_wall)
            .max_by(|&i, &j| {
                (reach(i, up), reach(i, right))
                    .partial_cmp(&(reach(j, up), reach(j, right)))
                    .unwrap_or(std::cmp::Ordering::Equal)
            })
            .unwrap_or(0)
    }

    /// Internal forces `f = sum B^T s` (3 per block) from the interface forces.
    pub fn internal_forces(&self, forces: &[[f64; 3]], out: &mut [f64]) {
        out.fill(0.0);
        for (it, s) in self.interfaces.iter().zip(forces) {
            let d = it.dofs();
            for k in 0..6 {
                out[d[k]] += it.b_mat[0][k] * s[0] + it.b_mat[1][k] * s[1] + it.b_mat[2][k] * s[2];
            }
        }
    }
}

