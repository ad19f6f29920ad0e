//! The model: blocks, interfaces, joint laws, supports and loads.
//!
//! Block numbering: wall blocks `0..n_wall` in the order given, then the base (if any), then
//! the top beam (if any). Each block has 3 dof at its centroid: u1, u2 \[m\], phi \[rad\]; the global
//! dof index of dof k of block i is `3 i + k`.
//!
//! ```
//! use masonry_dem::geometry::Rect;
//! use masonry_dem::model::{Model, ModelSpec};
//! let spec = ModelSpec { blocks: vec![Rect::new(0.0, 0.0, 0.4, 0.175)], ..ModelSpec::default() };
//! let model = Model::new(spec).unwrap();
//! assert_eq!(model.n_wall(), 1);
//! assert_eq!(model.interfaces().len(), 1); // the block on the base
//! ```

use crate::error::{non_negative, positive, Error, Result};
use crate::geometry::{Rect, MAX_BLOCKS};
use crate::interface::{detect, BlockKind, Family, Interface};
use crate::joint::{JointLaw, Kinds, Section};

/// The joint law of each family; a family without its own law uses `default`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct JointLaws {
    pub default: JointLaw,
    pub bed: Option<JointLaw>,
    pub head: Option<JointLaw>,
    pub base: Option<JointLaw>,
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
}

/// The live load pattern scaled by the load multiplier lambda.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LiveLoad {
    /// A horizontal force lambda * W_i on every wall block, towards +x (lambda dimensionless).
    HorizontalWeight,
    /// A horizontal force of lambda newtons on the top beam, towards +x.
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
    /// Wall blocks.
    pub blocks: Vec<Rect>,
    /// Out-of-plane thickness s \[m\].
    pub thickness: f64,
    /// Density [kg/m3].
    pub density: f64,
    /// A fixed rigid foundation under the lowest blocks, spanning the wall.
    pub base: bool,
    pub top: Option<TopBeam>,
    pub joints: JointLaws,
    /// [m/s2]
    pub gravity: f64,
    pub live: LiveLoad,
}

impl Default for ModelSpec {
    fn default() -> Self {
        ModelSpec {
            blocks: vec![],
            thickness: 1.0,
            density: 1000.0,
            base: true,
            top: None,
            joints: JointLaws::default(),
            gravity: 9.81,
            live: LiveLoad::HorizontalWeight,
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
    rects: Vec<Rect>,
    kinds: Vec<BlockKind>,
    n_wall: usize,
    base: Option<usize>,
    top: Option<usize>,
    thickness: f64,
    gravity: f64,
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
}

impl Model {
    /// Checks, before an analysis allocates, that the memory it needs can be had
    /// ([`crate::error::check_memory`]); `what` names the analysis.
    pub(crate) fn check_analysis_memory(&self, what: &str) -> Result<()> {
        let n = self.n_blocks() as f64;
        crate::error::check_memory(
            &format!("{what} of {} blocks", self.n_blocks()),
            n * crate::error::ANALYSIS_BYTES_PER_BLOCK,
        )
    }

    /// Builds and checks a model; the error names the key or block at fault.
    pub fn new(spec: ModelSpec) -> Result<Model> {
        Model::new_with(spec, &mut || true)
    }

    /// [`Model::new`], calling `poll` every few thousand blocks of the search for interfaces (a
    /// second at a million blocks): `false` stops it with [`Error::Interrupted`].
    pub fn new_with(spec: ModelSpec, poll: &mut dyn FnMut() -> bool) -> Result<Model> {
        positive("geometry.thickness", spec.thickness)?;
        positive("geometry.density", spec.density)?;
        non_negative("loads.gravity", spec.gravity)?;
        if spec.blocks.is_empty() {
            return Err(Error::input("geometry: the wall has no blocks"));
        }
        if spec.blocks.len() > MAX_BLOCKS {
            return Err(crate::geometry::too_many_blocks("geometry", spec.blocks.len() as f64));
        }
        crate::error::check_memory(
            &format!("a model of {} blocks", spec.blocks.len()),
            spec.blocks.len() as f64 * crate::error::MODEL_BYTES_PER_BLOCK,
        )?;
        for (i, r) in spec.blocks.iter().enumerate() {
            r.validate(&format!("block {i}"))?;
        }
        spec.joints.default.validate("joints")?;
        for (name, law) in [
            ("bed", spec.joints.bed),
            ("head", spec.joints.head),
            ("base", spec.joints.base),
            ("top", spec.joints.top),
        ] {
            if let Some(l) = law {
                l.validate(&format!("joints.{name}"))?;
            }
        }
        let n_wall = spec.blocks.len();
        let (mut xmin, mut ymin, mut xmax, mut ymax, mut hmax) =
            (f64::MAX, f64::MAX, f64::MIN, f64::MIN, 0.0f64);
        for r in &spec.blocks {
            xmin = xmin.min(r.x0);
            ymin = ymin.min(r.y0);
            xmax = xmax.max(r.x1);
            ymax = ymax.max(r.y1);
            hmax = hmax.max(r.height());
        }
        let mut rects = spec.blocks.clone();
        let mut kinds = vec![BlockKind::Wall; n_wall];
        let base = spec.base.then(|| {
            rects.push(Rect::new(xmin, ymin - hmax, xmax, ymin));
            kinds.push(BlockKind::Base);
            rects.len() - 1
        });
        if let Some(t) = &spec.top {
            for (k, v) in t.force.iter().enumerate() {
                if !v.is_finite() {
                    return Err(Error::input(format!(
                        "top.force[{k}] must be finite, got {v}"
                    )));
                }
            }
        }
        let top = spec.top.map(|_| {
            rects.push(Rect::new(xmin, ymax, xmax, ymax + hmax));
            kinds.push(BlockKind::Top);
            rects.len() - 1
        });
        if spec.live == LiveLoad::TopHorizontal && top.is_none() {
            return Err(Error::input(
                "loads.live = \"top_horizontal\" needs a top beam ([top])",
            ));
        }
        if spec.live == LiveLoad::HorizontalWeight && spec.gravity == 0.0 {
            return Err(Error::input("loads.live = \"horizontal_weight\" needs gravity > 0 (the live load is lambda times the weights)"));
        }
        let name = |i: usize| block_name(i, n_wall, base, top, &rects);
        let interfaces = detect(&rects, &kinds, name, poll)?;
        let mut touched = vec![false; rects.len()];
        for it in &interfaces {
            touched[it.a] = true;
            touched[it.b] = true;
        }
        if let Some(i) = (0..n_wall).find(|&i| !touched[i]) {
            return Err(Error::input(format!(
                "{} touches no other block",
                block_name(i, n_wall, base, top, &rects)
            )));
        }
        if let Some(t) = top {
            if !touched[t] {
                return Err(Error::input("top beam touches no block"));
            }
        }
        let nb = rects.len();
        let s = spec.thickness;
        let mass: Vec<f64> = rects.iter().map(|r| spec.density * r.area() * s).collect();
        let inertia: Vec<f64> = rects
            .iter()
            .zip(&mass)
            .map(|(r, m)| m * (r.width().powi(2) + r.height().powi(2)) / 12.0)
            .collect();
        check_masses(&mass, &inertia, |i| block_name(i, n_wall, base, top, &rects))?;
        // the base and the top beam carry no self-weight: the beam's load is its `force`
        let weight: Vec<f64> = (0..nb)
            .map(|i| {
                if i < n_wall {
                    mass[i] * spec.gravity
                } else {
                    0.0
                }
            })
            .collect();
        if let Some(i) = weight.iter().position(|w| !w.is_finite()) {
            return Err(Error::input(format!(
                "{}: its weight (mass {:e} kg times loads.gravity = {} m/s2) is not finite",
                block_name(i, n_wall, base, top, &rects),
                mass[i],
                spec.gravity
            )));
        }
        let sections = interfaces.iter().map(|it| Section::new(it.l, s)).collect();
        let mut fixed = vec![false; 3 * nb];
        if let Some(b) = base {
            fixed[3 * b..3 * b + 3].fill(true);
        }
        let mut f_dead = vec![0.0; 3 * nb];
        let mut f_live = vec![0.0; 3 * nb];
        for i in 0..n_wall {
            f_dead[3 * i + 1] = -weight[i];
        }
        let mut held = vec![];
        if let (Some(t), Some(tb)) = (top, &spec.top) {
            fixed[3 * t + 2] = tb.rotation_fixed;
            if tb.vertical_held {
                held.push(3 * t + 1);
            }
            f_dead[3 * t] = tb.force[0];
            f_dead[3 * t + 1] = tb.force[1];
        }
        match spec.live {
            LiveLoad::HorizontalWeight => (0..n_wall).for_each(|i| f_live[3 * i] = weight[i]),
            LiveLoad::TopHorizontal => f_live[3 * top.unwrap()] = 1.0,
        }
        let model = Model {
            rects,
            kinds,
            n_wall,
            base,
            top,
            thickness: s,
            gravity: spec.gravity,
            live: spec.live,
            laws: spec.joints,
            mass,
            inertia,
            weight,
            interfaces,
            sections,
            fixed,
            prescribed: vec![0.0; 3 * nb],
            f_dead,
            f_live,
            held,
        };
        model.check_scales()?;
        Ok(model)
    }

    /// The key of the joint law of interfaces of family `f` ("joints" or "joints.bed", ...).
    fn law_key(&self, f: Family) -> String {
        let set = match f {
            Family::Bed => self.laws.bed.is_some(),
            Family::Head => self.laws.head.is_some(),
            Family::Base => self.laws.base.is_some(),
            Family::Top => self.laws.top.is_some(),
        };
        if set {
            format!("joints.{}", f.name())
        } else {
            "joints".into()
        }
    }

    /// Refuses numbers each valid alone whose scales together leave the solvers nothing to
    /// resolve: interface stiffnesses that overflow, and joints so soft that the dead loads
    /// alone would move the wall out of the small-displacement model.
    fn check_scales(&self) -> Result<()> {
        for (k, (it, sec)) in self.interfaces.iter().zip(&self.sections).enumerate() {
            if !crate::joint::stiffness(self.laws.of(it.family), sec).iter().all(|k| k.is_finite()) {
                return Err(Error::input(format!(
                    "interface {k} ({} / {}): its stiffness ({}.normal_stiffness or shear_stiffness times the area, thickness x length = {:e} m2) is not finite: check geometry.thickness and the joints' stiffness",
                    self.block_name(it.a),
                    self.block_name(it.b),
                    self.law_key(it.family),
                    sec.area
                )));
            }
        }
        let size = self.size();
        // the dead loads are carried to the base through its interfaces: their settlement
        let base_stiffness: f64 = self
            .interfaces
            .iter()
            .zip(&self.sections)
            .filter(|(it, _)| it.family == Family::Base)
            .map(|(it, sec)| self.laws.of(it.family).normal_stiffness * sec.area)
            .sum();
        let vertical: f64 = self.f_dead.iter().skip(1).step_by(3).sum::<f64>().abs();
        if base_stiffness > 0.0 {
            let settlement = vertical / base_stiffness;
            if !(settlement <= SETTLEMENT_LIMIT * size) {
                return Err(Error::input(format!(
                    "under its dead loads ({vertical:.3e} N) the wall would sink about {settlement:.3e} m into its base joints (joints' normal_stiffness x base area = {base_stiffness:.3e} N/m), more than {SETTLEMENT_LIMIT} of its size ({size:.3e} m): the small-displacement model does not hold; check loads.gravity, geometry.density and the joints' stiffness"
                )));
            }
        }
        Ok(())
    }

    /// Refuses, for the analyses that raise lambda until collapse, joints whose cohesion or
    /// tensile strength is more than [`STRENGTH_RANGE`] times the stress of the wall's own
    /// weight: no multiplier within their range breaks them, and the answer would be about the
    /// solvers' limits, not the wall (time histories accept them: a joint meant never to yield).
    pub(crate) fn check_strength_range(&self) -> Result<()> {
        if self.live == LiveLoad::HorizontalWeight {
            let (x0, x1) = self.rects.iter().fold((f64::MAX, f64::MIN), |(a, b), r| (a.min(r.x0), b.max(r.x1)));
            let stress = self.weight.iter().sum::<f64>() / ((x1 - x0) * self.thickness);
            for it in &self.interfaces {
                let l = self.laws.of(it.family);
                for (name, value) in [("cohesion", l.cohesion), ("tensile_strength", l.tensile_strength)] {
                    if value > STRENGTH_RANGE * stress {
                        return Err(Error::input(format!(
                            "{}.{name} = {value:e} Pa is more than {STRENGTH_RANGE:e} times the stress of the wall's own weight ({stress:.3e} Pa at its base): no load within the solvers' range can break such a joint (for joints meant not to fail, 1e3 times that stress is plenty)",
                            self.law_key(it.family)
                        )));
                    }
                }
            }
        }
        Ok(())
    }

    /// Dofs held, at the position they reach under the dead loads, from then on (the top beam's
    /// vertical dof when it is held). Both solvers fix them once the dead state is found.
    pub fn held_after_dead(&self) -> &[usize] {
        &self.held
    }

    /// Fixes dof `dof` (0: u1, 1: u2, 2: phi) of block `block` at `value` [m or rad].
    pub fn fix(&mut self, block: usize, dof: usize, value: f64) -> Result<()> {
        if block >= self.rects.len() {
            return Err(Error::input(format!(
                "fix: block {block} does not exist (the model has {} blocks)",
                self.rects.len()
            )));
        }
        if dof > 2 {
            return Err(Error::input(format!(
                "fix: dof {dof} of block {block} must be 0 (u1), 1 (u2) or 2 (phi)"
            )));
        }
        if !value.is_finite() {
            return Err(Error::input(format!(
                "fix: value of dof {dof} of block {block} must be finite, got {value}"
            )));
        }
        self.fixed[3 * block + dof] = true;
        self.prescribed[3 * block + dof] = value;
        Ok(())
    }

    /// Refuses a model in which some wall block is not connected, through interfaces, to a block
    /// with a fixed dof (the base, or a user support).
    pub fn check_supports(&self) -> Result<()> {
        let nb = self.rects.len();
        let mut adj: Vec<Vec<usize>> = vec![vec![]; nb];
        for it in &self.interfaces {
            adj[it.a].push(it.b);
            adj[it.b].push(it.a);
        }
        let mut seen: Vec<bool> = (0..nb)
            .map(|i| self.fixed[3 * i..3 * i + 3].iter().any(|&f| f))
            .collect();
        if !seen.iter().any(|&s| s) {
            return Err(Error::input(
                "the wall has no support: no base ([base] kind = \"none\") and no fixed dof",
            ));
        }
        let mut stack: Vec<usize> = (0..nb).filter(|&i| seen[i]).collect();
        while let Some(i) = stack.pop() {
            for &j in &adj[i] {
                if !seen[j] {
                    seen[j] = true;
                    stack.push(j);
                }
            }
        }
        let loose: Vec<usize> = (0..nb).filter(|&i| !seen[i]).collect();
        if !loose.is_empty() {
            let names: Vec<String> = loose.iter().take(5).map(|&i| self.block_name(i)).collect();
            return Err(Error::input(format!(
                "{} block(s) not connected to any support: {}{}",
                loose.len(),
                names.join(", "),
                if loose.len() > 5 { ", ..." } else { "" }
            )));
        }
        Ok(())
    }

    /// A label for messages: "block 7 [x0, y0, x1, y1]", "the base" or "the top beam".
    pub fn block_name(&self, i: usize) -> String {
        block_name(i, self.n_wall, self.base, self.top, &self.rects)
    }

    pub fn n_wall(&self) -> usize {
        self.n_wall
    }
    /// All blocks: wall blocks, then base, then top beam.
    pub fn n_blocks(&self) -> usize {
        self.rects.len()
    }
    pub fn rects(&self) -> &[Rect] {
        &self.rects
    }
    /// The size of the model \[m\]: the larger side of the box around every block (base and top
    /// beam included). It does not depend on where the wall stands.
    pub fn size(&self) -> f64 {
        let (mut x0, mut y0, mut x1, mut y1) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
        for r in &self.rects {
            x0 = x0.min(r.x0);
            y0 = y0.min(r.y0);
            x1 = x1.max(r.x1);
            y1 = y1.max(r.y1);
        }
        (x1 - x0).max(y1 - y0)
    }
    pub fn kinds(&self) -> &[BlockKind] {
        &self.kinds
    }
    pub fn base(&self) -> Option<usize> {
        self.base
    }
    pub fn top(&self) -> Option<usize> {
        self.top
    }
    pub fn thickness(&self) -> f64 {
        self.thickness
    }
    pub fn gravity(&self) -> f64 {
        self.gravity
    }
    pub fn live(&self) -> LiveLoad {
        self.live
    }
    /// Mass of each block \[kg\].
    pub fn mass(&self) -> &[f64] {
        &self.mass
    }
    /// Rotary inertia of each block about its centroid [kg m2].
    pub fn inertia(&self) -> &[f64] {
        &self.inertia
    }
    /// Weight of each block \[N\] (0 for the base and the top beam).
    pub fn weight(&self) -> &[f64] {
        &self.weight
    }
    pub fn interfaces(&self) -> &[Interface] {
        &self.interfaces
    }
    pub fn sections(&self) -> &[Section] {
        &self.sections
    }
    /// The joint law of interface `k`.
    pub fn law(&self, k: usize) -> &JointLaw {
        self.laws.of(self.interfaces[k].family)
    }
    /// The kinds of the interfaces (the distinct pairs of law and section, at most
    /// [`Kinds::MAX`] in the table), each with the return mapping's constants.
    pub fn joint_kinds(&self) -> Kinds {
        Kinds::new(self.interfaces.iter().zip(&self.sections).map(|(it, s)| (it.family as u8, self.laws.of(it.family), s)), Kinds::MAX)
    }
    /// Whether some interface's law has cohesion or tensile strength.
    pub fn laws_are_strong(&self) -> bool {
        (0..self.interfaces.len()).any(|k| self.law(k).is_strong())
    }
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

    /// The default control block: the top beam if there is one, else the highest wall block at
    /// the right end (largest y1, then largest x1).
    pub fn default_control_block(&self) -> usize {
        if let Some(t) = self.top {
            return t;
        }
        (0..self.n_wall)
            .max_by(|&i, &j| {
                let (a, b) = (&self.rects[i], &self.rects[j]);
                (a.y1, a.x1)
                    .partial_cmp(&(b.y1, b.x1))
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

/// Refuses a block whose mass or rotary inertia is zero (it underflowed) or not finite (it
/// overflowed): the explicit solver divides by them and the weights are loads.
fn check_masses(mass: &[f64], inertia: &[f64], name: impl Fn(usize) -> String) -> Result<()> {
    for (i, (&m, &j)) in mass.iter().zip(inertia).enumerate() {
        if !(m.is_finite() && m > 0.0 && j.is_finite() && j > 0.0) {
            return Err(Error::input(format!(
                "{}: its mass ({m:e} kg) or rotary inertia ({j:e} kg m2) is zero or not finite: check geometry.density, geometry.thickness and the block's size",
                name(i)
            )));
        }
    }
    Ok(())
}

fn block_name(
    i: usize,
    n_wall: usize,
    base: Option<usize>,
    top: Option<usize>,
    rects: &[Rect],
) -> String {
    if Some(i) == base {
        "the base".into()
    } else if Some(i) == top {
        "the top beam".into()
    } else if i < n_wall {
        format!("block {i} {}", rects[i].label())
    } else {
        format!("block {i}")
    }
}
