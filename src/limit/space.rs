//! The program of a model in 3D, in the point-contact form (Livesley; Portioli et al.): each
//! corner of a contact polygon carries a force in Coulomb's cone `|T| <= mu N`, and torsion and
//! biaxial bending come out of the corners' positions.
//!
//! The corner's variables are a second-order cone `z0 >= |(z1, z2)|` (the interior point's cones
//! of three dimensions) and its force `z0 n + mu (z1 t1 + z2 t2)`: the cone itself, the same
//! strength in every direction of sliding, as the explicit solver's joint law has it. (An
//! inscribed pyramid of eight sides would keep cos(22.5 deg) = 0.924 of it midway between two
//! sides, with 32 variables per contact against the cones' 12.)
//!
//! Joints with strength: the contact's cohesion `c A` and tensile strength `ft A` are shared by
//! its corners as the explicit solver's joint law shares them ([`crate::joint::corner_shares`],
//! tributary areas: a share `w_i` each), and a corner's domain is the plane's at one of its two
//! points: `N_i <= h w_i` (a tension cut-off, `h = min(ft A, c A / mu)`) and `|T_i| <= c A w_i -
//! mu N_i`. That is a vertex (the cut-off's tension, a constant), Coulomb's cone from it, and a
//! disc of shear of radius `r_i = (c A - mu h) w_i` (a cone whose first coordinate an equation
//! of its own holds at `r_i`): `{N >= -h, |T| <= r + mu (N + h)}` in compression is exactly the
//! cone plus the disc. The shares' centroid being the polygon's, the corners' tension is the
//! polygon's uniform tensile strength in N and in bending about both axes. Strengths enter at
//! their peak (no loss at failure), as in the plane.

use super::*;
use crate::joint::corner_shares;
use crate::space::{Contact, Model3};

/// Equations per contact: the six dofs of each of its two blocks (then one per disc of
/// cohesion, see [`Discs`]).
const ROWS3: usize = 12;

/// The program of a model in 3D: the generic [`Lp`] whose corners carry each contact's cone
/// generators (unit normal, mu times each tangent, in global axes).
pub(super) struct Space {
    pub(super) lp: Lp,
    /// per contact with strength, its cut-off (scaled) and its corners' shares
    vertex: Vec<Option<(f64, Vec<f64>)>>,
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

impl Space {
    /// The program of `model`, once its joints and contacts are checked and the memory it needs
    /// ([`memory_need`]) can be had.
    pub(super) fn new(model: &Model3) -> Result<Space> {
        let nb = model.n_blocks();
        let contacts = model.contacts();
        let (what, bytes) = memory_need(model);
        crate::error::check_memory(&what, bytes)?;
        // equations: one per free dof
        let fixed = model.fixed();
        let mut eq = vec![None; 6 * nb];
        let mut n = 0;
        for (d, e) in eq.iter_mut().enumerate() {
            if !fixed[d] {
                *e = Some(n);
                n += 1;
            }
        }
        let n_dofs = n;
        let (fd, fl) = (model.dead_load(), model.live_load());
        let trans = |v: &[f64]| (0..nb).flat_map(|i| (0..3).map(move |r| v[6 * i + r].abs())).fold(0.0, f64::max);
        let live_max = trans(fl);
        let mut force = trans(fd);
        if force <= 0.0 {
            force = if live_max > 0.0 { live_max } else { 1.0 };
        }
        let m = contacts.len();
        let length = contacts.iter().map(|c| c.area.sqrt()).sum::<f64>() / m.max(1) as f64;
        let length = if length > 0.0 { length } else { 1.0 };
        let live = if live_max > 0.0 { live_max } else { 1.0 };
        let row = |d: usize| if d % 6 >= 3 { 1.0 / length } else { 1.0 };
        let free = |d: &usize| eq[*d].is_some();
        let mut f_dead: Vec<f64> = (0..6 * nb).filter(free).map(|d| fd[d] * row(d) / force).collect();
        let mut f_live: Vec<f64> = (0..6 * nb).filter(free).map(|d| fl[d] * row(d) / live).collect();
        // each contact's strengths over the force scale (capped as the plane's, see
        // `STRENGTH_CAP`): its cut-off h and its corners' shares, and the discs' radii
        let total = f_dead.iter().map(|f| f.abs()).sum::<f64>() + f_live.iter().map(|f| f.abs()).sum::<f64>();
        let cap = STRENGTH_CAP * total.max(1.0);
        let mut strength = Vec::with_capacity(m);
        let mut radii = vec![];
        let mut discs = Discs::default();
        for (k, c) in contacts.iter().enumerate() {
            let law = model.law(k);
            let (ca, fa) = ((law.cohesion * c.area / force).min(cap), (law.tensile_strength * c.area / force).min(cap));
            let strong = ca > 0.0 || fa > 0.0;
            let h = if law.friction * fa > ca { ca / law.friction } else { fa };
            let w = if strong { corner_shares(&c.corners, c.centroid, c.n).0 } else { vec![] };
            // a disc at each corner where the cone from the cut-off leaves a radius
            let r = ca - law.friction * h;
            discs.start.push(radii.len());
            discs.tangents.push([c.t1, c.t2]);
            if strong && r > 0.0 {
                radii.extend(w.iter().map(|wi| r * wi));
                discs.contact.extend(std::iter::repeat(k as u32).take(w.len()));
                discs.corner.extend(0..w.len());
            }
            strength.push(strong.then_some((h, w)));
        }
        discs.start.push(radii.len());
        if radii.is_empty() {
            discs = Discs::default();
        }
        // the discs' radii are held by equations after the dofs'
        f_dead.extend_from_slice(&radii);
        f_live.resize(f_dead.len(), 0.0);
        let n = n_dofs + radii.len();
        let most = (0..m).map(|k| discs.of(k).len()).max().unwrap_or(0);
        let rows = ROWS3 + most;
        let mut dofs = crate::error::try_with_capacity("the program's equations", rows * m)?;
        for (k, c) in contacts.iter().enumerate() {
            for blk in [c.a, c.b] {
                for r in 0..6 {
                    dofs.push(eq[6 * blk + r].map_or(NO_EQ, |e| e as u32));
                }
            }
            let own = discs.of(k);
            dofs.extend(own.clone().map(|d| (n_dofs + d) as u32));
            dofs.extend(std::iter::repeat(NO_EQ).take(most - own.len()));
        }
        let mut lp = Lp::new(eq, n, rows, 0, None, dofs, f_dead, f_live, (force, length, live))?;
        lp.cone = 3;
        let centroids = model.centroids();
        let mut gens = crate::error::try_with_capacity("the program's generators", 3 * m)?;
        let n_corners: usize = contacts.iter().map(|c| c.corners.len()).sum();
        let mut arms = crate::error::try_with_capacity("the program's corners", n_corners)?;
        let mut start = crate::error::try_with_capacity("the program's corners", m + 1)?;
        start.push(0);
        for (k, c) in contacts.iter().enumerate() {
            let mu = model.law(k).friction;
            gens.extend_from_slice(&[c.n, c.t1.map(|v| mu * v), c.t2.map(|v| mu * v)]);
            let first = arms.len();
            for &p in &c.corners {
                let arm = |i: usize| sub(p, centroids[i]).map(|v| v / length);
                arms.push([arm(c.a), arm(c.b)]);
            }
            // the cut-off's tension at each corner: a constant force -h w_i n on b (the rows'
            // convention: a force f on b is +f on a's rows, -f on b's)
            if let Some((h, w)) = &strength[k] {
                let pv = &mut lp.pv[rows * k..rows * k + ROWS3];
                for (j, wi) in w.iter().enumerate() {
                    let [ra, rb] = arms[first + j];
                    let f = c.n.map(|v| -h * wi * v);
                    let (ma, mb) = (cross(ra, f), cross(rb, f));
                    let v = [f[0], f[1], f[2], ma[0], ma[1], ma[2], -f[0], -f[1], -f[2], -mb[0], -mb[1], -mb[2]];
                    pv.iter_mut().zip(v).for_each(|(p, v)| *p += v);
                }
            }
            start.push(arms.len());
        }
        // the discs' corners, numbered among every corner
        for d in 0..discs.corner.len() {
            discs.corner[d] += start[discs.contact[d] as usize];
        }
        lp.corners = Some(Corners { start, sides: 3, gens, arms, discs });
        lp.regularize_frictionless((0..m).any(|k| model.law(k).friction == 0.0));
        Ok(Space { lp, vertex: strength })
    }

    /// Each contact's resultants in their own units: the force and moment (about the contact's
    /// centroid) that block b exerts on block a, in the contact's axes (n, t1, t2):
    /// (N, T1, T2, M_n, M_t1, M_t2), N > 0 in tension as in the plane.
    fn resultants(&self, model: &Model3, x: &[f64]) -> Vec<[f64; 6]> {
        let f = self.lp.force;
        model
            .contacts()
            .iter()
            .enumerate()
            .map(|(k, c)| {
                let (mut force, mut moment) = ([0.0; 3], [0.0; 3]);
                let cf = self.lp.corners.as_ref().expect("a program in corner form");
                let sides = cf.sides;
                let mut add = |p: [f64; 3], fp: [f64; 3]| {
                    let mp = cross(sub(p, c.centroid), fp);
                    (0..3).for_each(|i| {
                        force[i] += fp[i];
                        moment[i] += mp[i];
                    });
                };
                for (j, (q, &p)) in cf.of(k).zip(&c.corners).enumerate() {
                    let g = &cf.gens[sides * k..sides * (k + 1)];
                    // the cut-off's tension, then the cone's generators
                    let mut fp = self.vertex.get(k).and_then(|v| v.as_ref()).map_or([0.0; 3], |(h, w)| c.n.map(|v| h * w[j] * f * v));
                    for (j, gj) in g.iter().enumerate() {
                        let r = x[cf.var(q) + j] * f;
                        (0..3).for_each(|i| fp[i] -= r * gj[i]);
                    }
                    add(p, fp);
                }
                for d in cf.discs.of(k) {
                    let [t1, t2] = cf.discs.tangents[k];
                    let (z1, z2) = (x[cf.disc_var(d) + 1] * f, x[cf.disc_var(d) + 2] * f);
                    add(c.corners[cf.discs.corner[d] - cf.start[k]], std::array::from_fn(|i| -z1 * t1[i] - z2 * t2[i]));
                }
                let axes = [c.n, c.t1, c.t2];
                let mut s = [0.0; 6];
                for (a, ax) in axes.iter().enumerate() {
                    s[a] = dot3(force, *ax);
                    s[3 + a] = dot3(moment, *ax);
                }
                s
            })
            .collect()
    }

    /// The collapse mechanism: block velocities (vx, vy, vz, wx, wy, wz) from the duals, oriented
    /// so that the live load does positive work, largest block translation 1.
    fn mechanism(&self, model: &Model3, sol: &Solution) -> Vec<f64> {
        let nb = model.n_blocks();
        let mut v = self.lp.velocities(sol, 6);
        let big = (0..nb)
            .map(|i| dot3([v[6 * i], v[6 * i + 1], v[6 * i + 2]], [v[6 * i], v[6 * i + 1], v[6 * i + 2]]).sqrt())
            .fold(0.0, f64::max);
        let work = dot(&v, model.live_load());
        let scale = if big > 0.0 { work.signum() / big } else { 0.0 };
        v.iter_mut().for_each(|x| *x *= scale);
        v
    }

    /// The results of a solution: the multiplier, the forces at collapse, the mechanism from
    /// the duals and the joints it moves.
    pub(super) fn results(
        &self,
        model: &Model3,
        sol: &Solution,
        cert: Certificate,
        start: Instant,
    ) -> Results<[f64; 6]> {
        let nb = model.n_blocks();
        let lam = self.lp.lambda_of(sol);
        let (status, error) = self.lp.status(sol, lam);
        let collapse = status == Status::Collapse;
        let v = if collapse { self.mechanism(model, sol) } else { vec![0.0; 6 * nb] };
        let flags = model
            .contacts()
            .iter()
            .enumerate()
            .map(|(k, c)| if collapse { space_flags(c, model.centroids(), &v, model.law(k).dilatancy) } else { 0 })
            .collect();
        let block = |v: &[f64], i: usize| -> [f64; 6] { std::array::from_fn(|r| v[6 * i + r]) };
        Results {
            method: "limit",
            status,
            error,
            collapse_multiplier: if collapse { lam } else { f64::NAN },
            last_equilibrium: if collapse { lam } else { f64::NAN },
            curve_multiplier: vec![],
            curve_displacement: vec![],
            control_block: control_block(model),
            displacements: vec![[0.0; 6]; nb],
            mechanism: (0..nb).map(|i| block(&v, i)).collect(),
            interface_forces: self.resultants(model, &sol.x),
            interface_states: flags,
            broken: vec![false; self.lp.m],
            iterations: cert.iterations,
            steps: 0,
            elapsed_s: start.elapsed().as_secs_f64(),
            bracket: None,
            certificate: Some(cert),
        }
    }
}

/// What a limit analysis of `model` is called in a message of memory, and the memory it needs
/// \[bytes\] ([`crate::error::LIMIT_3D_BYTES_PER_BLOCK`]).
fn memory_need(model: &Model3) -> (String, f64) {
    let nb = model.n_blocks();
    (format!("a limit analysis of {nb} blocks"), nb as f64 * crate::error::LIMIT_3D_BYTES_PER_BLOCK)
}

/// The block whose displacement a curve would follow: the wall's highest (the first of equals).
pub(crate) fn control_block(model: &Model3) -> usize {
    let c = model.centroids();
    (0..model.n_wall()).fold(0, |best, i| if c[i][2] > c[best][2] { i } else { best })
}

/// The joint states that a mechanism's velocities `v` (largest block translation 1) give a
/// contact: open where every corner separates beyond the dilatancy of its slip, rocking where
/// some corners separate and others do not, sliding where a corner slips; motions below 1e-6
/// are rest.
fn space_flags(c: &Contact, centroids: &[[f64; 3]], v: &[f64], dilatancy: f64) -> u8 {
    let tol = 1e-6;
    let at = |i: usize, p: [f64; 3]| {
        let w = cross([v[6 * i + 3], v[6 * i + 4], v[6 * i + 5]], sub(p, centroids[i]));
        [v[6 * i] + w[0], v[6 * i + 1] + w[1], v[6 * i + 2] + w[2]]
    };
    let (mut open, mut closed, mut slip) = (0, 0, false);
    for &p in &c.corners {
        let d = sub(at(c.b, p), at(c.a, p));
        let dn = dot3(d, c.n);
        let dt = dot3(d, c.t1).hypot(dot3(d, c.t2));
        if dt > tol {
            slip = true;
        }
        if dn - dilatancy * dt > tol {
            open += 1;
        } else {
            closed += 1;
        }
    }
    if closed == 0 {
        return OPEN;
    }
    let mut f = 0;
    if slip {
        f |= SLIDING;
    }
    if open > 0 {
        f |= ROCKING;
    }
    f
}

/// Runs a limit analysis of a model in 3D, calling `monitor` after each interior-point
/// iteration (return `false` to stop: the result is then an `Err(Error::Interrupted)`).
///
/// Joints with dilatancy below friction give the associative program's optimum as an upper
/// bound, with the status `Estimate` (the non-associative sequence is the plane's alone).
pub fn limit_analysis_3d_with(
    model: &Model3,
    opts: &LimitOptions,
    monitor: &mut dyn FnMut(&LimitProgress) -> bool,
) -> Result<Results<[f64; 6]>> {
    validate(opts)?;
    model.check_live("limit analysis")?;
    model.check_supports()?;
    let start = Instant::now();
    // a large part of the memory `Space::new` checked that cannot be allocated all the same: the
    // same error
    let out_of_memory = |e: Error| match e {
        Error::OutOfMemory { .. } => {
            let (what, bytes) = memory_need(model);
            Error::OutOfMemory { what, bytes }
        }
        e => e,
    };
    let mut space = Space::new(model).map_err(out_of_memory)?;
    space.lp.start_threads(opts.threads)?;
    let sol = space.lp.solve(opts, 0, monitor)?;
    let non_assoc = (0..model.contacts().len()).any(|k| {
        let l = model.law(k);
        l.dilatancy < l.friction
    });
    let cert = Certificate {
        multiplier: f64::NAN,
        primal_residual: sol.primal,
        dual_residual: sol.dual,
        duality_gap: sol.gap,
        iterations: sol.iterations,
        upper_bound: if non_assoc { space.lp.lambda_of(&sol) } else { f64::NAN },
        sequence: 0,
        sequence_converged: false,
        peak_strengths: (0..model.contacts().len()).any(|k| model.law(k).is_strong()),
    };
    let mut res = space.results(model, &sol, cert, start);
    if let Some(c) = res.certificate.as_mut() {
        c.multiplier = res.collapse_multiplier;
    }
    if non_assoc && res.status == Status::Collapse {
        mark_estimate(&mut res);
    }
    Ok(res)
}

/// Runs a limit analysis of a model in 3D (see [`limit_analysis_3d_with`]).
pub fn limit_analysis_3d(model: &Model3, opts: &LimitOptions) -> Result<Results<[f64; 6]>> {
    limit_analysis_3d_with(model, opts, &mut |_| true)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::joint::JointLaw;
    use crate::model::JointLaws;
    use crate::space::{Box3, LiveLoad3, ModelSpec3};

    /// A squat box of friction 0.3 pushed at `phi` in plan: its sliding multiplier.
    fn sliding(phi: f64) -> f64 {
        let law = JointLaw { friction: 0.3, dilatancy: 0.3, ..JointLaw::default() };
        let model = Model3::new(&ModelSpec3 {
            blocks: vec![Box3::new(0.0, 0.0, 0.0, 1.0, 1.2, 0.5)],
            joints: JointLaws::uniform(law),
            live: LiveLoad3::HorizontalWeight { direction: phi },
            ..ModelSpec3::default()
        })
        .unwrap();
        limit_analysis_3d(&model, &LimitOptions::default()).unwrap().collapse_multiplier
    }

    #[test]
    fn coulombs_cone_slides_at_mu_in_every_direction_in_plan() {
        // overturning needs 1 / 0.5 = 2 at the least: the box slides, at mu whatever the
        // direction (at 22.5 deg an eight-sided pyramid along x would hold 0.3 cos(22.5 deg) =
        // 0.2772)
        for phi in [0.0, 22.5, 45.0, 67.5, 100.0, 200.0] {
            assert!((sliding(phi) - 0.3).abs() <= 1e-6 * 0.3, "{phi} deg: {}", sliding(phi));
        }
    }

    #[test]
    fn the_threads_give_the_same_results_to_the_bit() {
        // a U wall (facade 12 m, returns 4 m, 5 m high) of more contacts than the passes need to
        // run on several threads, pushed out of the facade's plane; dry, and with mortar (the
        // discs of cohesion and their equations on the threads too)
        let dry = JointLaw { friction: 0.7, dilatancy: 0.7, ..JointLaw::default() };
        for law in [dry, JointLaw { cohesion: 2e4, tensile_strength: 5e3, ..dry }] {
            let model = Model3::new(&ModelSpec3 {
                blocks: crate::space::u_wall(12.0, 5.0, 4.0, 0.25, 0.5, 0.25).unwrap(),
                joints: JointLaws::uniform(law),
                live: LiveLoad3::HorizontalWeight { direction: 90.0 },
                ..ModelSpec3::default()
            })
            .unwrap();
            assert!(model.contacts().len() >= 2000, "{} contacts", model.contacts().len());
            let run = |threads| limit_analysis_3d(&model, &LimitOptions { threads, ..LimitOptions::default() }).unwrap();
            let (one, two) = (run(1), run(2));
            assert_eq!(one.status, Status::Collapse);
            assert_eq!(one.iterations, two.iterations);
            assert_eq!(one.collapse_multiplier.to_bits(), two.collapse_multiplier.to_bits());
            let bits = |r: &Results<[f64; 6]>| r.mechanism.iter().chain(&r.interface_forces).flatten().map(|v| v.to_bits()).collect::<Vec<_>>();
            assert!(bits(&one) == bits(&two), "the mechanisms or the forces differ");
        }
    }
}
