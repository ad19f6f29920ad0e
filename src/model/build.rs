//! Building a [`Model`] from a [`ModelSpec`]: the checks of the input, the base and the top beam,
//! the interfaces, masses and loads, and the checks of scales that only the whole model shows.

use super::{JointLaws, LiveLoad, Model, ModelSpec, SETTLEMENT_LIMIT, STRENGTH_RANGE};
use crate::error::{non_negative, positive, Error, Result};
use crate::geometry::{Rect, MAX_BLOCKS};
use crate::interface::{detect, BlockKind, Family, Interface};
use crate::joint::Section;
use crate::shape::{contact_tolerance, Aabb, Area, Defect, Polygon};

/// The blocks of a model before its interfaces: the wall's, then the supports, the base and the
/// top beam, checked; and the contact tolerance.
struct Frame {
    polygons: Vec<Polygon>,
    kinds: Vec<BlockKind>,
    n_wall: usize,
    n_supports: usize,
    base: Option<usize>,
    top: Option<usize>,
    tol: f64,
}

impl Frame {
    fn name(&self, i: usize) -> String {
        block_name(i, self.n_wall, self.n_supports, self.base, self.top, &self.polygons)
    }
}

impl Model {
    /// Builds and checks a model; the error names the key or block at fault.
    pub fn new(spec: ModelSpec) -> Result<Model> {
        Model::new_with(spec, &mut || true)
    }

    /// [`Model::new`], calling `poll` every few thousand blocks of the search for interfaces (a
    /// second at a million blocks): `false` stops it with [`Error::Interrupted`].
    pub fn new_with(spec: ModelSpec, poll: &mut dyn FnMut() -> bool) -> Result<Model> {
        check_spec(&spec)?;
        let gravity_direction = unit_gravity(spec.gravity_direction)?;
        let frame = frame(&spec)?;
        let areas: Vec<Area> = frame.polygons.iter().map(Polygon::area_properties).collect();
        let mut centroids: Vec<[f64; 2]> = areas.iter().map(|a| a.centroid).collect();
        let s = spec.thickness;
        let mut mass: Vec<f64> = areas.iter().map(|a| spec.density * a.area * s).collect();
        let mut inertia: Vec<f64> = areas.iter().map(|a| spec.density * a.polar * s).collect();
        check_masses(&mass, &inertia, |i| frame.name(i))?;
        let mut weight = weights(&frame, &mass, spec.gravity)?;
        // the carried loads' masses, lumped before the interfaces take the centres as their blocks'
        super::check_carried_inside(&spec.carried, frame.tol, |i, p| outside(&frame.polygons[i], p), |i| frame.name(i))?;
        for (i, m) in super::lump_carried(&spec.carried, spec.gravity, &mut mass, &mut centroids) {
            inertia[i] += m[0][0] + m[1][1];
        }
        check_masses(&mass, &inertia, |i| frame.name(i))?;
        for (k, l) in spec.carried.iter().enumerate() {
            weight[l.block] += l.weight;
            if !weight[l.block].is_finite() {
                let key = super::carried::key(k);
                return Err(Error::input_at(key.clone(), format!("{key}: the weight of {} with its loads is not finite", frame.name(l.block))));
            }
        }
        let name = |i: usize| frame.name(i);
        let interfaces =
            detect(&frame.polygons, &centroids, &frame.kinds, gravity_direction, frame.tol, name, poll)?;
        check_touched(&frame, &interfaces)?;
        crate::error::check_weight(weight.iter().sum(), spec.density, spec.gravity)?;
        let sections = interfaces.iter().map(|it| Section::new(it.l, s)).collect();
        let nb = frame.polygons.len();
        let mut model = Model {
            polygons: frame.polygons,
            centroids,
            kinds: frame.kinds,
            n_wall: frame.n_wall,
            n_supports: frame.n_supports,
            base: frame.base,
            top: frame.top,
            thickness: s,
            gravity: spec.gravity,
            gravity_direction,
            live: spec.live,
            laws: spec.joints,
            mass,
            inertia,
            weight,
            interfaces,
            sections,
            fixed: vec![false; 3 * nb],
            prescribed: vec![0.0; 3 * nb],
            f_dead: vec![0.0; 3 * nb],
            f_live: vec![0.0; 3 * nb],
            held: vec![],
            carried: spec.carried.clone(),
        };
        model.supports_and_loads(&spec);
        model.check_scales()?;
        Ok(model)
    }

    /// The fixed dofs of the supports and the base, the top beam's supports, and the dead and live
    /// loads (the weights along gravity, the horizontal live load across it).
    fn supports_and_loads(&mut self, spec: &ModelSpec) {
        for b in self.supports().chain(self.base) {
            self.fixed[3 * b..3 * b + 3].fill(true);
        }
        let (g, h) = (self.gravity_direction, self.horizontal());
        for i in 0..self.n_wall {
            self.f_dead[3 * i] = self.weight[i] * g[0];
            self.f_dead[3 * i + 1] = self.weight[i] * g[1];
        }
        if let (Some(t), Some(tb)) = (self.top, &spec.top) {
            self.fixed[3 * t + 2] = tb.rotation_fixed;
            if tb.vertical_held {
                self.held.push(3 * t + 1);
            }
            self.f_dead[3 * t] = tb.force[0];
            self.f_dead[3 * t + 1] = tb.force[1];
        }
        match spec.live {
            LiveLoad::HorizontalWeight => (0..self.n_wall).for_each(|i| {
                self.f_live[3 * i] = self.weight[i] * h[0];
                self.f_live[3 * i + 1] = self.weight[i] * h[1];
            }),
            LiveLoad::TopHorizontal => {
                let t = self.top.expect("checked by frame()");
                self.f_live[3 * t..3 * t + 2].copy_from_slice(&h);
            }
        }
    }

    /// The key of the joint law of interfaces of family `f` ("joints" or "joints.bed", ...).
    fn law_key(&self, f: Family) -> String {
        law_key(&self.laws, f)
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
        // along gravity, which may point any way
        let g = self.gravity_direction;
        let vertical: f64 = (0..self.n_blocks()).map(|i| self.f_dead[3 * i] * g[0] + self.f_dead[3 * i + 1] * g[1]).sum::<f64>().abs();
        check_settlement(vertical, self.base_stiffness(), size, "loads.gravity, geometry.density and the joints' stiffness")
    }

    /// The normal stiffness of the base's interfaces together \[N/m\]: the wall's vertical
    /// stiffness as one body on its base (0 without a base).
    pub(crate) fn base_stiffness(&self) -> f64 {
        self.interfaces
            .iter()
            .zip(&self.sections)
            .filter(|(it, _)| it.family == Family::Base)
            .map(|(it, sec)| self.laws.of(it.family).normal_stiffness * sec.area)
            .sum()
    }

    /// Refuses, for the analyses that raise lambda until collapse, joints whose cohesion or
    /// tensile strength is more than [`STRENGTH_RANGE`] times the stress of the wall's own
    /// weight: no multiplier within their range breaks them, and the answer would be about the
    /// solvers' limits, not the wall (time histories accept them: a joint meant never to yield).
    pub(crate) fn check_strength_range(&self) -> Result<()> {
        if self.live == LiveLoad::HorizontalWeight {
            // the wall's width across gravity
            let h = self.horizontal();
            let (x0, x1) = self.polygons[..self.n_wall]
                .iter()
                .flat_map(|p| p.vertices())
                .map(|v| v[0] * h[0] + v[1] * h[1])
                .fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(x), b.max(x)));
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

    /// Checks, before an analysis allocates, that the memory it needs can be had
    /// ([`crate::error::check_memory`]); `what` names the analysis.
    pub(crate) fn check_analysis_memory(&self, what: &str) -> Result<()> {
        let n = self.n_blocks() as f64;
        crate::error::check_memory(
            &format!("{what} of {} blocks", self.n_blocks()),
            n * crate::error::ANALYSIS_BYTES_PER_BLOCK,
        )
    }
}

/// The key of the joint law of family `f` in `laws` ("joints" or "joints.bed", ...): the
/// family's own where it has one.
pub(crate) fn law_key(laws: &JointLaws, f: Family) -> String {
    let set = match f {
        Family::Bed => laws.bed.is_some(),
        Family::Head => laws.head.is_some(),
        Family::Base => laws.base.is_some(),
        Family::Top => laws.top.is_some(),
    };
    if set {
        format!("joints.{}", f.name())
    } else {
        "joints".into()
    }
}

/// Refuses dead loads whose vertical sum `vertical` \[N\] would sink a wall of size `size` \[m\]
/// into base joints of normal stiffness `base_stiffness` \[N/m\] (none: 0, nothing checked) by
/// more than [`SETTLEMENT_LIMIT`] of its size; the message ends "check {`check`}".
pub(crate) fn check_settlement(vertical: f64, base_stiffness: f64, size: f64, check: &str) -> Result<()> {
    if base_stiffness > 0.0 {
        let settlement = vertical / base_stiffness;
        if !(settlement <= SETTLEMENT_LIMIT * size) {
            return Err(Error::input(format!(
                "under its dead loads ({vertical:.3e} N) the wall would sink about {settlement:.3e} m into its base joints (joints' normal_stiffness x base area = {base_stiffness:.3e} N/m), more than {SETTLEMENT_LIMIT} of its size ({size:.3e} m): the small-displacement model does not hold; check {check}"
            )));
        }
    }
    Ok(())
}

/// The checks of the spec's numbers, blocks and laws, each alone, before anything is built.
fn check_spec(spec: &ModelSpec) -> Result<()> {
    positive("geometry.thickness", spec.thickness)?;
    positive("geometry.density", spec.density)?;
    non_negative("loads.gravity", spec.gravity)?;
    if spec.blocks.is_empty() {
        return Err(Error::input("geometry: the wall has no blocks"));
    }
    super::check_carried(&spec.carried, spec.blocks.len(), spec.gravity)?;
    if spec.blocks.len() > MAX_BLOCKS {
        return Err(crate::geometry::too_many_blocks("geometry", spec.blocks.len() as f64));
    }
    crate::error::check_memory(
        &format!("a model of {} blocks", spec.blocks.len()),
        spec.blocks.len() as f64 * crate::error::MODEL_BYTES_PER_BLOCK,
    )?;
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
    Ok(())
}

/// The direction of gravity made a unit vector, or the refusal of a zero or non-finite one.
fn unit_gravity(g: [f64; 2]) -> Result<[f64; 2]> {
    let l = g[0].hypot(g[1]);
    if !(l.is_finite() && l > 0.0) {
        return Err(Error::input_at(
            "loads.gravity_direction",
            format!("loads.gravity_direction must be a finite non-zero vector, got [{}, {}]", g[0], g[1]),
        ));
    }
    Ok(if l == 1.0 { g } else { [g[0] / l, g[1] / l] })
}

/// The error of a block that is not a convex polygon, naming it.
fn defect(name: String, d: Defect) -> Error {
    Error::input(format!("{name}: {}", d.reason))
}

/// The wall's blocks and the supports, checked, with the base under the wall and the top beam
/// over it (each as wide as the box around the wall blocks and as high as the highest block's
/// box), checked against the live load that needs them; the contact tolerance from the size of
/// them all.
fn frame(spec: &ModelSpec) -> Result<Frame> {
    let (n_wall, n_supports) = (spec.blocks.len(), spec.supports.len());
    let given: Vec<&Polygon> = spec.blocks.iter().chain(&spec.supports).collect();
    let name = |i: usize, p: &Polygon| {
        if i < n_wall {
            format!("block {i} {}", p.label())
        } else {
            format!("support {} {}", i - n_wall, p.label())
        }
    };
    for (i, p) in given.iter().enumerate() {
        p.check_finite().map_err(|d| defect(name(i, p), d))?;
    }
    let mut wall = Aabb::around(&[]);
    let mut hmax = 0.0f64;
    for p in &spec.blocks {
        let b = p.aabb();
        wall = wall.union(&b);
        hmax = hmax.max(b.max[1] - b.min[1]);
    }
    let (xmin, ymin, xmax, ymax) = (wall.min[0], wall.min[1], wall.max[0], wall.max[1]);
    let mut kinds = vec![BlockKind::Wall; n_wall];
    kinds.resize(n_wall + n_supports, BlockKind::Support);
    let mut extra: Vec<Polygon> = vec![];
    let base = spec.base.then(|| {
        extra.push(Rect::new(xmin, ymin - hmax, xmax, ymin).into());
        kinds.push(BlockKind::Base);
        kinds.len() - 1
    });
    if let Some(t) = &spec.top {
        for (k, v) in t.force.iter().enumerate() {
            if !v.is_finite() {
                return Err(Error::input_at("top.force", format!(
                    "top.force[{k}] must be finite, got {v}"
                )));
            }
        }
    }
    let top = spec.top.map(|_| {
        extra.push(Rect::new(xmin, ymax, xmax, ymax + hmax).into());
        kinds.push(BlockKind::Top);
        kinds.len() - 1
    });
    if spec.live == LiveLoad::TopHorizontal && top.is_none() {
        return Err(Error::input_at(
            "loads.live",
            "loads.live = \"top_horizontal\" needs a top beam ([top])",
        ));
    }
    if spec.live == LiveLoad::HorizontalWeight && spec.gravity == 0.0 {
        return Err(Error::input_at("loads.live", "loads.live = \"horizontal_weight\" needs gravity > 0 (the live load is lambda times the weights)"));
    }
    let size = given.iter().copied().chain(&extra).fold(wall, |b, p| b.union(&p.aabb())).size();
    let tol = contact_tolerance(size);
    let mut polygons = Vec::with_capacity(given.len() + extra.len());
    for (i, p) in given.iter().copied().chain(&extra).enumerate() {
        let checked = p.checked(tol).map_err(|d| match kinds[i] {
            BlockKind::Base => defect("the base".into(), d),
            BlockKind::Top => defect("the top beam".into(), d),
            _ => defect(name(i, p), d),
        })?;
        polygons.push(checked);
    }
    Ok(Frame { polygons, kinds, n_wall, n_supports, base, top, tol })
}

/// Refuses a wall block, or the top beam, that no interface reaches.
fn check_touched(frame: &Frame, interfaces: &[Interface]) -> Result<()> {
    let mut touched = vec![false; frame.polygons.len()];
    for it in interfaces {
        touched[it.a] = true;
        touched[it.b] = true;
    }
    if let Some(i) = (0..frame.n_wall).find(|&i| !touched[i]) {
        return Err(Error::input(format!("{} touches no other block", frame.name(i))));
    }
    if let Some(t) = frame.top {
        if !touched[t] {
            return Err(Error::input("top beam touches no block"));
        }
    }
    Ok(())
}

/// The weight of each block \[N\]: the supports, the base and the top beam carry none (the beam's
/// load is its `force`).
fn weights(frame: &Frame, mass: &[f64], gravity: f64) -> Result<Vec<f64>> {
    let weight: Vec<f64> = (0..frame.polygons.len())
        .map(|i| if i < frame.n_wall { mass[i] * gravity } else { 0.0 })
        .collect();
    if let Some(i) = weight.iter().position(|w| !w.is_finite()) {
        return Err(Error::input(format!(
            "{}: its weight (mass {:e} kg times loads.gravity = {} m/s2) is not finite",
            frame.name(i),
            mass[i],
            gravity
        )));
    }
    Ok(weight)
}

/// How far `p` lies outside the convex polygon `poly` (counter-clockwise) \[m\]: the largest
/// distance beyond the line of an edge, 0 or less inside.
fn outside(poly: &Polygon, p: [f64; 2]) -> f64 {
    let v = poly.vertices();
    (0..v.len())
        .map(|k| {
            let (a, b) = (v[k], v[(k + 1) % v.len()]);
            let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
            ((p[0] - a[0]) * dy - (p[1] - a[1]) * dx) / dx.hypot(dy)
        })
        .fold(f64::MIN, f64::max)
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

/// "block 7 [x0, y0, x1, y1]" (a wall block, named by its rectangle or its polygon), "support 0
/// ..." (the first support), "the base" or "the top beam".
pub(super) fn block_name(
    i: usize,
    n_wall: usize,
    n_supports: usize,
    base: Option<usize>,
    top: Option<usize>,
    polygons: &[Polygon],
) -> String {
    if Some(i) == base {
        "the base".into()
    } else if Some(i) == top {
        "the top beam".into()
    } else if i < n_wall {
        format!("block {i} {}", polygons[i].label())
    } else if i < n_wall + n_supports {
        format!("support {} {}", i - n_wall, polygons[i].label())
    } else {
        format!("block {i}")
    }
}
