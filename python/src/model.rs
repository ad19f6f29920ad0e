//! `Model`: building it, its geometry, and its analyses (static, limit, explicit, time history).

use crate::*;

/// A wall of rigid blocks joined by zero-thickness Mohr-Coulomb interfaces.
///
/// blocks: the wall's blocks [m]: an (n, 4) array of axis-aligned rectangles [x0, y0, x1, y1],
///     or a list whose items are each a rectangle [x0, y0, x1, y1] or a convex polygon (a list
///     of k >= 3 vertices [x, y], or a (k, 2) array, in either orientation). A concave stone is
///     given as convex parts.
/// thickness: out-of-plane thickness [m]; density [kg/m3].
/// base: True puts a fixed rigid foundation under the lowest blocks, spanning the wall; None
///     (the default): True unless supports are given.
/// supports: fixed blocks (abutments, springers, an inclined plane) [m], as blocks: each a
///     polygon (or a rectangle); the wall's joints with them are of the "base" family.
/// gravity_direction: [gx, gy], the direction of gravity (made a unit vector), [0, -1] by
///     default; the horizontal live load acts along it turned by +90 degrees ([1, 0] by default).
/// top_rotation: None (no top beam), "fixed" or "free": a rigid, weightless beam resting on the
///     highest blocks and spanning the wall; top_force: dead force [Fx, Fy] on it [N].
/// top_vertical: "free" (the vertical force on the beam stays top_force[1]; the beam may rise) or
///     "held" (the beam's vertical position is held once the dead loads are on, so the vertical
///     force becomes a reaction that changes with the live load; quasi-static analyses only).
/// joints: {family: law} with family in "default", "bed", "head", "base", "top"; a law is a dict
///     with keys normal_stiffness [N/m3], shear_stiffness [N/m3], friction [-], cohesion [Pa],
///     tensile_strength [Pa], dilatancy [-] (tan psi), fracture_energy_tension and
///     fracture_energy_shear [N/m] (both 0: brittle, cohesion and tensile strength lost at the
///     first failure; both > 0: exponential softening). Missing keys of a family law fall back
///     to "default"; missing keys of "default" fall back to 1e10, 1e10, 0.65, 0, 0, 0, 0, 0.
/// gravity [m/s2]; live: "horizontal_weight" (lambda * W_i on every block towards +x) or
///     "top_horizontal" (lambda newtons on the top beam towards +x); +x: gravity_direction
///     turned by +90 degrees.
/// carried: loads carried by wall blocks (a floor's reaction), a list of (block, [x, y], weight):
///     a weight [N] along gravity resting at a point [m] of the block (0-based), whose mass
///     weight / gravity moves with it: it takes the live load in proportion to its weight, and
///     the block's centroid (where its dofs are), mass and inertia are those of block and loads.
/// Raises InputError naming the key, block or interface on bad input.
#[pyclass(name = "Model", module = "masonry_dem._core", subclass)]
pub(crate) struct PyModel {
    pub(crate) inner: Arc<Model>,
}

#[pymethods]
impl PyModel {
    #[new]
    #[pyo3(signature = (blocks, thickness=None, density=None, base=None, top_rotation=None, top_force=None, joints=None, gravity=None, live=None, top_vertical=None, supports=None, gravity_direction=None, carried=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        blocks: &Bound<'_, PyAny>,
        thickness: Option<f64>,
        density: Option<f64>,
        base: Option<bool>,
        top_rotation: Option<&str>,
        top_force: Option<Vec<f64>>,
        joints: Option<&Bound<'_, PyDict>>,
        gravity: Option<f64>,
        live: Option<&str>,
        top_vertical: Option<&str>,
        supports: Option<&Bound<'_, PyAny>>,
        gravity_direction: Option<Vec<f64>>,
        carried: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let d = ModelSpec::default();
        let top = TopBeam::from_keys(top_rotation, top_force.as_deref(), top_vertical).map_err(to_py)?;
        let supports = match supports {
            Some(s) if !s.is_none() => polygons_from(s, "supports", "support")?,
            _ => vec![],
        };
        let gravity_direction = match gravity_direction.as_deref() {
            None => d.gravity_direction,
            Some(&[x, y]) => [x, y],
            Some(v) => {
                return Err(InputError::new_err(format!(
                    "gravity_direction: expected 2 numbers [gx, gy], got {}",
                    v.len()
                )))
            }
        };
        let spec = ModelSpec {
            blocks: polygons_from(blocks, "blocks", "block")?,
            base: base.unwrap_or(supports.is_empty()),
            supports,
            thickness: thickness.unwrap_or(d.thickness),
            density: density.unwrap_or(d.density),
            top,
            joints: laws_from(joints)?,
            gravity: gravity.unwrap_or(d.gravity),
            gravity_direction,
            live: live.map_or(Ok(d.live), str::parse).map_err(to_py)?,
            carried: carried_from(carried)?,
        };
        // the GIL released (a million blocks take seconds), polling Ctrl-C in this thread
        let mut raised = None;
        let built = py.detach(|| {
            guarded(|| {
                Model::new_with(spec, &mut || match Python::attach(|py| py.check_signals()) {
                    Ok(()) => true,
                    Err(e) => {
                        raised = Some(e);
                        false
                    }
                })
            })
        });
        if let Some(e) = raised {
            return Err(e);
        }
        Ok(PyModel { inner: Arc::new(built?) })
    }

    /// Fix dof (0: u1 [m], 1: u2 [m], 2: phi [rad]) of a block at a prescribed value.
    #[pyo3(signature = (block, dof, value=0.0))]
    fn fix(&mut self, block: usize, dof: usize, value: f64) -> PyResult<()> {
        Arc::make_mut(&mut self.inner).fix(block, dof, value).map_err(to_py)
    }

    /// The loads carried by wall blocks: a list of (block, [x, y], weight [N]).
    #[getter]
    fn carried(&self) -> Vec<(usize, [f64; 2], f64)> {
        carried_to_py(self.inner.carried())
    }

    /// The live load: "horizontal_weight" (lambda times each block's weight) or "top_horizontal" (lambda newtons on the top beam).
    #[getter]
    fn live(&self) -> &'static str {
        self.inner.live().as_str()
    }

    /// 2: a wall in the plane (Model3D's is 3).
    #[getter]
    fn dimension(&self) -> usize {
        2
    }
    /// Number of wall blocks (supports, base and top beam not counted).
    #[getter]
    fn n_blocks(&self) -> usize {
        self.inner.n_wall()
    }
    /// Number of interfaces (the joints between blocks, and with the base and the top beam).
    #[getter]
    fn n_interfaces(&self) -> usize {
        self.inner.interfaces().len()
    }
    /// Index of the base (the fixed foundation) among the blocks; None without one.
    #[getter]
    fn base_index(&self) -> Option<usize> {
        self.inner.base()
    }
    /// Index of the top beam among the blocks; None without one.
    #[getter]
    fn top_index(&self) -> Option<usize> {
        self.inner.top()
    }
    /// The block the solvers follow when no control block is given: the top beam if any, else the highest wall block at the right end.
    #[getter]
    fn default_control_block(&self) -> usize {
        self.inner.default_control_block()
    }
    /// (n_all, 4) bounding box [x0, y0, x1, y1] of every block [m] (a rectangle's is itself), wall
    /// blocks first, then supports, then base, then top beam.
    #[getter]
    fn rects<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        rects_to_py(py, &self.inner.rects())
    }
    /// Every block's polygon [m], a (k_i, 2) array of vertices counter-clockwise from the lowest
    /// (the leftmost of the lowest), in the order of rects: wall blocks, supports, base, top beam.
    #[getter]
    fn polygons<'py>(&self, py: Python<'py>) -> Vec<Bound<'py, PyArray2<f64>>> {
        polygons_to_py(py, self.inner.polygons())
    }
    /// (n_all, 2) centroid of every block [m], where its dofs are: its centre of mass (the polygon's, moved by the loads it carries).
    #[getter]
    fn centroids<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        rows_of(py, self.inner.centroids())
    }
    /// What each block is: "wall", "support", "base" or "top".
    #[getter]
    fn block_kinds(&self) -> Vec<&'static str> {
        self.inner.kinds().iter().map(|k| k.name()).collect()
    }
    /// Indices of the supports (the fixed blocks given) among the blocks.
    #[getter]
    fn support_indices(&self) -> Vec<usize> {
        self.inner.supports().collect()
    }
    /// [gx, gy]: the direction of gravity, a unit vector.
    #[getter]
    fn gravity_direction(&self) -> [f64; 2] {
        self.inner.gravity_direction()
    }
    /// (n_all,) weight of each block [N], with the loads it carries (0 for supports, base and top beam).
    #[getter]
    fn weights<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.weight().to_vec().into_pyarray(py)
    }
    /// (m, 2) block indices (a, b) of each interface; the normal points from a to b.
    #[getter]
    fn interface_blocks<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<i64>> {
        let it = self.inner.interfaces();
        let flat: Vec<i64> = it.iter().flat_map(|i| [i.a as i64, i.b as i64]).collect();
        Array2::from_shape_vec((it.len(), 2), flat)
            .unwrap()
            .into_pyarray(py)
    }
    /// (m, 5): centroid x, y [m], normal nx, ny, length l [m].
    #[getter]
    fn interface_geometry<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let it = self.inner.interfaces();
        let flat: Vec<f64> = it
            .iter()
            .flat_map(|i| [i.c[0], i.c[1], i.n[0], i.n[1], i.l])
            .collect();
        Array2::from_shape_vec((it.len(), 5), flat)
            .unwrap()
            .into_pyarray(py)
    }
    /// Family of each interface: "bed", "head", "base" (with the base or a support) or "top".
    #[getter]
    fn interface_family(&self) -> Vec<&'static str> {
        self.inner
            .interfaces()
            .iter()
            .map(|i| i.family.name())
            .collect()
    }

    /// Static incremental analysis (Newton with the consistent tangent).
    ///
    /// Options left out (None) take the core's defaults: steps 200, tolerance 1e-4,
    /// max_iterations 50 (Newton iterations before a step is cut).
    ///
    /// control="load": raise lambda until collapse, following the equilibrium path in steps of
    /// the live load's work; the collapse multiplier is the peak or the plateau of lambda, to
    /// `tolerance` (relative). control="displacement": drive the horizontal displacement of
    /// control_block (default: the top beam if any, else the highest block at the right end;
    /// one held along x, the base, is refused) to max_displacement [m] in `steps` increments,
    /// through the peak and after it; without max_displacement (None), from 2 mm on by as much
    /// again, `steps` increments each time, until a peak or a plateau of lambda.
    /// Returns Results with status "collapse" (with its evidence: a peak, a plateau with no
    /// equilibrium just above, and on associative dry joints the limit-analysis multiplier),
    /// "completed" (the requested displacement reached, lambda still rising), "stalled" (load
    /// control stopped converging below the limit-analysis multiplier), "displacement_limit"
    /// (the path left the small-displacement model, a tenth of the wall's size, with lambda
    /// still rising) or "failed"; collapse_multiplier is NaN unless "collapse", and
    /// last_equilibrium holds the largest lambda found in equilibrium. Never raises for a
    /// solver failure (the reason is in Results.error).
    /// Runs in a thread of its own, the GIL released. Ctrl-C raises KeyboardInterrupt within a
    /// fraction of a second, with the partial Results as the exception's `results` attribute
    /// (None when the run is inside one long sparse factorization, 10^5 blocks and more: it
    /// then finishes that in the background and stops); an exception raised by `progress` is
    /// raised the same way.
    /// progress: optional callable(step, multiplier, displacement, fraction) called after each
    /// converged step (fraction in [0, 1] under displacement control, NaN otherwise).
    #[pyo3(signature = (control=None, steps=None, max_displacement=None, control_block=None, tolerance=None, max_iterations=None, progress=None))]
    #[allow(clippy::too_many_arguments)]
    fn solve_static(
        &self,
        py: Python<'_>,
        control: Option<&str>,
        steps: Option<i64>,
        max_displacement: Option<f64>,
        control_block: Option<usize>,
        tolerance: Option<f64>,
        max_iterations: Option<i64>,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Py<PyResults>> {
        let defaults = StaticOptions::default();
        let control = Control::from_keys(control, max_displacement, defaults.control).map_err(to_py)?;
        let opts = StaticOptions {
            control,
            until_collapse: max_displacement.is_none(),
            steps: steps.map_or(Ok(defaults.steps), |v| count("analysis.steps", v, 1))?,
            tolerance: tolerance.unwrap_or(defaults.tolerance),
            max_iterations: max_iterations.map_or(Ok(defaults.max_iterations), |v| count("max_iterations", v, 1))?,
            control_block,
            ..defaults
        };
        analyse(py, &self.inner, progress, move |model, monitor| {
            static_solver::solve_with(model, &opts, monitor).map(PyResults::from)
        })
    }

    /// Limit analysis (the static theorem): the largest lambda for which interface forces inside
    /// the joints' strength domains balance the dead loads plus lambda times the live load, as a
    /// linear program solved by a primal-dual interior point method on the stiffness matrix's
    /// sparsity pattern. Exact for dry associative joints (dilatancy = friction); for dilatancy
    /// below friction the associative optimum is an upper bound (certificate["upper_bound"]) and
    /// the multiplier is a non-associative estimate from a sequence of at most max_sequence
    /// programs (0: the associative bound only), status "estimate": neither bound, converged or
    /// not, its value in last_equilibrium and certificate["multiplier"], the bound in
    /// certificate["upper_bound"], the convergence in certificate["sequence_converged"].
    /// Mortar joints enter with their peak strengths.
    ///
    /// tolerance: the interior point stops when its scaled residuals and relative duality gap are
    /// all below this (0 < tolerance < 0.01; default 1e-8). max_iterations: interior-point
    /// iterations per program (default 200); max_sequence default 50.
    /// Returns Results with method "limit" and status "collapse" (collapse_multiplier, the
    /// mechanism's normalised block velocities in `mechanism`, the forces at collapse in
    /// interface_forces, the crack pattern in interface_states), "no_equilibrium" (the dead loads
    /// alone cannot be carried), "unbounded" (no mechanism within the range of multipliers),
    /// "estimate" (dilatancy below friction, see above) or "failed" (the interior point did not
    /// converge); the reason is in Results.error, and
    /// collapse_multiplier is NaN unless the status is "collapse". No load path: the curve is
    /// empty, displacements are zeros and steps is 0; iterations counts interior-point iterations.
    /// Releases the GIL; Ctrl-C stops it between iterations and raises KeyboardInterrupt, whose
    /// `results` attribute is a Results with status "failed" and error "interrupted by the
    /// user" (no multiplier, no certificate).
    /// progress: optional callable(iteration, multiplier, nan, nan) called after each
    /// interior-point iteration (iterations counted over all the programs; multiplier: the
    /// current estimate). An exception raised by it stops the analysis and is raised again.
    ///
    /// follow_mechanism=True: the collapse mechanism is then followed to the end, the blocks
    /// moved by finite steps of it (each turned exactly about its instantaneous centre), the
    /// contacts found again (along edges and at points) and the limit analysis solved again on
    /// the moved geometry: the large-displacement capacity curve. The Results are the first
    /// analysis's (multiplier, mechanism, certificate) with `curve_displacement` (the control
    /// block's horizontal displacement [m]) and `curve_multiplier` (lambda on the moved geometry)
    /// from (0, lambda_0) down to lambda = 0, `displacements` the blocks' finite motion at the
    /// curve's end (u1, u2 [m], phi [rad]) and `steps` the steps taken; a curve that stops short
    /// of zero says why in Results.error (the status stays the first analysis's). follow_step:
    /// the largest displacement of a block's vertex in one step [m] (default: the model's size
    /// over 200); a step that fails is halved. follow_steps: steps at most (default 1000).
    ///
    /// move_support (0-based among the supports; an arch's abutments 0 and 1) with
    /// move_direction ("+x", "-x", "+y" or "-y"): that support moved along the direction (its
    /// dof made free, a unit force on it the live load), followed to where no equilibrium exists
    /// (follow_step default: the model's size over 1000). lambda is then the force the wall
    /// exerts on the support along its movement [N] (an arch's thrust against a spread), the
    /// least of every admissible state: collapse_multiplier its value as built,
    /// curve_displacement the support's movement [m], curve_multiplier the force on the moved
    /// geometry, last_equilibrium the force at the curve's end. Status "collapse" where a moved
    /// geometry within a step past the end has no equilibrium at any force on the support (the
    /// wall falls there), "completed" (the steps ran out) or "failed" (no such proof), with the
    /// reason in Results.error.
    #[pyo3(signature = (tolerance=None, max_iterations=None, max_sequence=None, progress=None, follow_mechanism=false, follow_step=None, follow_steps=None, move_support=None, move_direction=None))]
    #[allow(clippy::too_many_arguments)]
    fn solve_limit(
        &self,
        py: Python<'_>,
        tolerance: Option<f64>,
        max_iterations: Option<i64>,
        max_sequence: Option<i64>,
        progress: Option<Py<PyAny>>,
        follow_mechanism: bool,
        follow_step: Option<f64>,
        follow_steps: Option<i64>,
        move_support: Option<usize>,
        move_direction: Option<&str>,
    ) -> PyResult<Py<PyResults>> {
        let defaults = LimitOptions::default();
        let opts = LimitOptions {
            tolerance: tolerance.unwrap_or(defaults.tolerance),
            max_iterations: max_iterations.map_or(Ok(defaults.max_iterations), |v| count("max_iterations", v, 1))?,
            max_sequence: max_sequence.map_or(Ok(defaults.max_sequence), |v| count("max_sequence", v, 0))?,
            ..defaults
        };
        let movement = movement_from(move_support, move_direction)?;
        if movement.is_some() && follow_mechanism {
            return Err(InputError::new_err("follow_mechanism: a support's movement is followed already; give move_support or follow_mechanism, not both"));
        }
        let follow = follow_options(follow_mechanism || movement.is_some(), follow_step, follow_steps)?;
        limit_run(py, &self.inner, progress, move |model, monitor| match (movement, follow) {
            (Some(m), Some(follow)) => limit::follow_movement(model, &m, &opts, &follow, monitor),
            (_, Some(follow)) => limit::follow_mechanism(model, &opts, &follow, monitor),
            _ => limit::limit_analysis_with(model, &opts, monitor),
        }, |model, start| interrupted_limit(model.n_blocks(), model.interfaces().len(), model.default_control_block(), [0.0; 3], start))
    }

    /// Quasi-static analysis with the explicit (molecular dynamics) solver; the same Results
    /// as solve_static, with method "dynamic" and `iterations` = time steps.
    ///
    /// Options left out (None) take the core's defaults: steps 200, max_displacement 0.002 m,
    /// tolerance 1e-3, unbalanced_ratio 1e-5, damping "local" with coefficient 0.8, safety 0.8,
    /// threads 0 (all cores).
    ///
    /// control="load": each load level is relaxed until |unbalanced| <= unbalanced_ratio *
    /// |applied|; the collapse multiplier is bracketed to `tolerance`. control="displacement":
    /// the control block is driven to max_displacement in `steps` stages, lambda following from
    /// its equation. damping: "local" (Cundall, coefficient alpha in [0, 1)), "viscous"
    /// (mass-proportional, coefficient c [1/s]) or "none". time_step [s]: None for the automatic
    /// stable step (safety * the stability limit); a user step above the limit is an InputError.
    /// threads: threads of the interface loop (0: all cores). large_rotations: finite rotations
    /// of the blocks, each stage's equilibrium found on the moved geometry (the
    /// large-displacement capacity curve under displacement control; its drive is quasi-static
    /// in small stages only: keep steps at 200 or more); default False, the linearized
    /// kinematics. contact_update: the contacts found again as the blocks move, as in
    /// Model.simulate (large_rotations=True needed); default False. Status and multipliers as in
    /// solve_static (here the path always ends at max_displacement, default 2 mm). Releases the
    /// GIL; Ctrl-C raises KeyboardInterrupt with the partial Results as its `results` attribute.
    /// progress: as in solve_static, every few thousand steps.
    ///
    /// move_support with move_direction (as in solve_limit): that support driven along the
    /// direction by max_displacement [m] (> 0, required) in `steps` stages under
    /// control="displacement" (the default then), each relaxed with the support held; the wall
    /// falls at the first stage that does not settle (a block moving 1% of the model's size, or
    /// the unbalanced ratio not settling within the steps allowed): status "collapse" with
    /// `bracket` the movements of the last stage that settled and of the first that did not,
    /// else "completed". The curve: the support's movement [m] and the force the wall exerts on
    /// it along the movement [N] (from the dead state); large_rotations=True follows the moved
    /// geometry.
    #[pyo3(signature = (control=None, steps=None, max_displacement=None, control_block=None, tolerance=None, unbalanced_ratio=None, damping=None, damping_coefficient=None, time_step=None, safety=None, threads=None, large_rotations=None, contact_update=None, progress=None, move_support=None, move_direction=None))]
    #[allow(clippy::too_many_arguments)]
    fn solve_dynamic(
        &self,
        py: Python<'_>,
        control: Option<&str>,
        steps: Option<i64>,
        max_displacement: Option<f64>,
        control_block: Option<usize>,
        tolerance: Option<f64>,
        unbalanced_ratio: Option<f64>,
        damping: Option<&str>,
        damping_coefficient: Option<f64>,
        time_step: Option<f64>,
        safety: Option<f64>,
        threads: Option<i64>,
        large_rotations: Option<bool>,
        contact_update: Option<bool>,
        progress: Option<Py<PyAny>>,
        move_support: Option<usize>,
        move_direction: Option<&str>,
    ) -> PyResult<Py<PyResults>> {
        let movement = movement_from(move_support, move_direction)?;
        if movement.is_some() && max_displacement.is_none() {
            return Err(InputError::new_err("max_displacement: a support's movement by the explicit solver needs how far the support moves [m]"));
        }
        if movement.is_some() && control_block.is_some() {
            return Err(InputError::new_err("control_block: a support's movement follows its support; leave control_block out"));
        }
        let control = match (movement, control) {
            (Some(_), None) => Some("displacement"),
            _ => control,
        };
        let opts = explicit_options(
            (control, steps, max_displacement, control_block, tolerance),
            (unbalanced_ratio, damping, damping_coefficient),
            (time_step, safety, threads),
            (large_rotations, contact_update),
        )?;
        analyse(py, &self.inner, progress, move |model, monitor| {
            match movement {
                Some(m) => explicit::solve_movement(model, &m, &opts, monitor),
                None => explicit::solve_with(model, &opts, monitor),
            }
            .map(PyResults::from)
        })
    }

    /// Time history with the explicit solver. Options left out (None) take the core's
    /// defaults: safety 0.8, damping "none" (coefficient 0), live_multiplier 0, a record every
    /// record_interval = 0.001 s, large_rotations True, threads 0 (all cores).
    ///
    /// Free motion from initial conditions
    /// (initial_displacements / initial_velocities: (n_all, 3) arrays of u1 [m], u2 [m],
    /// phi [rad] and their rates) and/or the ground's motion: base_acceleration (horizontal) and
    /// vertical_acceleration (upwards), each (times [s], accelerations [m/s2]), linear between
    /// samples and zero outside them; the blocks move in the frame of the base (displacements
    /// relative to the ground). live_multiplier: lambda held constant. large_rotations: block
    /// kinematics with finite rotations (needed for rocking); False uses the linearized
    /// kinematics of the static solver. Impacts lose energy by the joints' restitution (joint
    /// key "restitution", default 0.3: Housner's impact of a rocking block); the time step
    /// is lowered for the contact dashpots this takes. rayleigh=(alpha [1/s], beta [s]): Rayleigh
    /// damping alpha M + beta K (masonry_dem.rayleigh_damping from two modes), the beta K part as
    /// dashpots at the closed interfaces; instead of damping / damping_coefficient. Records every record_interval seconds
    /// or every record_every-th step (not both); Model.record_size gives the memory up front.
    /// contact_update (default True, with large_rotations; False: the contacts of the wall as built): the contacts found again as the
    /// blocks move (new contacts dry, with the joints' restitution; a contact found again keeps
    /// its history) and a ground plane at the top of the base (without a base, at the lowest
    /// point), reaching five model sizes beyond the blocks, onto which falling blocks come to rest.
    /// Releases the GIL; Ctrl-C stops it and raises KeyboardInterrupt, with the TimeHistory
    /// computed so far as its `results` attribute.
    /// progress: optional callable(step, time [s], nan, fraction done).
    #[pyo3(signature = (duration, time_step=None, safety=None, damping=None, damping_coefficient=None, initial_displacements=None, initial_velocities=None, base_acceleration=None, live_multiplier=None, record_every=None, large_rotations=None, threads=None, progress=None, vertical_acceleration=None, record_interval=None, rayleigh=None, contact_update=None))]
    #[allow(clippy::too_many_arguments)]
    fn simulate(
        &self,
        py: Python<'_>,
        duration: f64,
        time_step: Option<f64>,
        safety: Option<f64>,
        damping: Option<&str>,
        damping_coefficient: Option<f64>,
        initial_displacements: Option<&Bound<'_, PyAny>>,
        initial_velocities: Option<&Bound<'_, PyAny>>,
        base_acceleration: Option<&Bound<'_, PyAny>>,
        live_multiplier: Option<f64>,
        record_every: Option<i64>,
        large_rotations: Option<bool>,
        threads: Option<i64>,
        progress: Option<Py<PyAny>>,
        vertical_acceleration: Option<&Bound<'_, PyAny>>,
        record_interval: Option<f64>,
        rayleigh: Option<(f64, f64)>,
        contact_update: Option<bool>,
    ) -> PyResult<Py<PyTimeHistory>> {
        let mut opts = dynamic_options::<3>(
            duration,
            time_step,
            safety,
            (damping, damping_coefficient, rayleigh),
            (initial_displacements, initial_velocities),
            (base_acceleration, None, vertical_acceleration),
            live_multiplier,
            (record_every, record_interval),
            large_rotations,
            threads,
        )?;
        opts.contact_update = contact_update.unwrap_or(opts.contact_update);
        analyse(py, &self.inner, progress, move |model, monitor| {
            explicit::simulate_with(model, &opts, monitor).map(PyTimeHistory::from)
        })
    }

    /// (records, bytes) that Model.simulate with these options would hold (its time step as
    /// simulate chooses it); refuses what simulate refuses.
    #[pyo3(signature = (duration, time_step=None, record_every=None, record_interval=None))]
    fn record_size(&self, duration: f64, time_step: Option<f64>, record_every: Option<i64>, record_interval: Option<f64>) -> PyResult<(usize, f64)> {
        let opts = DynamicOptions { duration, time_step, record: recording(record_every, record_interval)?, ..DynamicOptions::default() };
        explicit::record_size(&self.inner, &opts).map_err(to_py)
    }


    /// The stability limit of the explicit solver's time step [s] (Gershgorin bound); with
    /// time_history=True, that of Model.simulate: lowered for the contact dashpots of the
    /// joints' restitution (the factor sqrt(1 + z^2) - z with z = 3 zeta, zeta the dashpot's
    /// damping ratio) and, with contact_update (True, simulate's default), for a block touching
    /// fixed bodies along every edge.
    #[pyo3(signature = (time_history=false, contact_update=true))]
    fn critical_time_step(&self, time_history: bool, contact_update: bool) -> f64 {
        if time_history {
            explicit::history_time_step_limit(&self.inner, 0.0, contact_update)
        } else {
            explicit::critical_time_step(&self.inner)
        }
    }

    fn __repr__(&self) -> String {
        format!(
            "Model({} blocks, {} interfaces)",
            self.inner.n_wall(),
            self.inner.interfaces().len()
        )
    }
}

/// The options of a quasi-static explicit analysis (`Model.solve_dynamic`, `Model3D.solve_dynamic`), those left
/// out (None) the core's defaults.
#[allow(clippy::type_complexity)]
pub(crate) fn explicit_options(
    (control, steps, max_displacement, control_block, tolerance): (Option<&str>, Option<i64>, Option<f64>, Option<usize>, Option<f64>),
    (unbalanced_ratio, damping, damping_coefficient): (Option<f64>, Option<&str>, Option<f64>),
    (time_step, safety, threads): (Option<f64>, Option<f64>, Option<i64>),
    (large_rotations, contact_update): (Option<bool>, Option<bool>),
) -> PyResult<ExplicitOptions> {
    let defaults = ExplicitOptions::default();
    Ok(ExplicitOptions {
        control: Control::from_keys(control, max_displacement, defaults.control).map_err(to_py)?,
        steps: steps.map_or(Ok(defaults.steps), |v| count("analysis.steps", v, 1))?,
        tolerance: tolerance.unwrap_or(defaults.tolerance),
        unbalanced_ratio: unbalanced_ratio.unwrap_or(defaults.unbalanced_ratio),
        damping: Damping::from_keys(damping, damping_coefficient, defaults.damping).map_err(to_py)?,
        time_step,
        safety: safety.unwrap_or(defaults.safety),
        threads: threads.map_or(Ok(defaults.threads), |v| count("threads", v, 0))?,
        control_block,
        large_rotations: large_rotations.unwrap_or(defaults.large_rotations),
        contact_update: contact_update.unwrap_or(defaults.contact_update),
        ..defaults
    })
}

/// The options of limit analysis along the mechanism, or None when it is not asked for (the
/// step and the steps are then refused if given: they would be ignored).
/// A support's movement from its keywords (both or neither).
fn movement_from(support: Option<usize>, direction: Option<&str>) -> PyResult<Option<SupportMovement>> {
    match (support, direction) {
        (None, None) => Ok(None),
        (Some(support), Some(d)) => Ok(Some(SupportMovement { support, direction: d.parse().map_err(to_py)? })),
        (Some(_), None) => Err(InputError::new_err("move_direction: a support's movement needs its direction (\"+x\", \"-x\", \"+y\" or \"-y\")")),
        (None, Some(_)) => Err(InputError::new_err("move_support: move_direction needs the support that moves (0-based among the supports)")),
    }
}

pub(crate) fn follow_options(follow: bool, step: Option<f64>, steps: Option<i64>) -> PyResult<Option<limit::FollowOptions>> {
    if !follow {
        if step.is_some() || steps.is_some() {
            return Err(InputError::new_err("follow_step and follow_steps are options of follow_mechanism=True"));
        }
        return Ok(None);
    }
    let defaults = limit::FollowOptions::default();
    let step = match step {
        Some(v) if !(v.is_finite() && v > 0.0) => return Err(InputError::new_err(format!("follow_step must be a length > 0 m, got {v}"))),
        Some(v) => v,
        None => defaults.step,
    };
    let max_steps = steps.map_or(Ok(defaults.max_steps), |v| count("follow_steps", v, 1))?;
    if max_steps > limit::MAX_FOLLOW_STEPS {
        return Err(InputError::new_err(format!("follow_steps must be at most {}, got {max_steps}", limit::MAX_FOLLOW_STEPS)));
    }
    Ok(Some(limit::FollowOptions { step, max_steps }))
}

/// The recording of a time history: `record_every` steps or `record_interval` seconds (not
/// both); neither: the core's default.
pub(crate) fn recording(record_every: Option<i64>, record_interval: Option<f64>) -> PyResult<Recording> {
    match (record_every, record_interval) {
        (Some(_), Some(_)) => Err(InputError::new_err("give record_every (steps) or record_interval (seconds), not both")),
        (Some(k), None) => Ok(Recording::Every(count("record_every", k, 1)?)),
        (None, Some(i)) => Ok(Recording::Interval(i)),
        (None, None) => Ok(DynamicOptions::<[f64; 3]>::default().record),
    }
}

/// An acceleration history `(times, accelerations)` from Python, `what` naming it in errors.
fn series(o: Option<&Bound<'_, PyAny>>, what: &str) -> PyResult<Option<(Vec<f64>, Vec<f64>)>> {
    match o.filter(|o| !o.is_none()) {
        None => Ok(None),
        Some(o) => o
            .extract::<(Vec<f64>, Vec<f64>)>()
            .map(Some)
            .map_err(|_| InputError::new_err(format!("{what}: expected (times, accelerations), two sequences of numbers"))),
    }
}

/// The options of a time history (`Model.simulate`, W = 3; `Model3D.simulate`, W = 6: initial conditions of W
/// numbers per block), those left out (None) the core's defaults; the base's accelerations along x, y (3D only)
/// and z.
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
pub(crate) fn dynamic_options<const W: usize>(
    duration: f64,
    time_step: Option<f64>,
    safety: Option<f64>,
    (damping, damping_coefficient, rayleigh): (Option<&str>, Option<f64>, Option<(f64, f64)>),
    (initial_displacements, initial_velocities): (Option<&Bound<'_, PyAny>>, Option<&Bound<'_, PyAny>>),
    (base_acceleration, base_acceleration_y, vertical_acceleration): (Option<&Bound<'_, PyAny>>, Option<&Bound<'_, PyAny>>, Option<&Bound<'_, PyAny>>),
    live_multiplier: Option<f64>,
    (record_every, record_interval): (Option<i64>, Option<f64>),
    large_rotations: Option<bool>,
    threads: Option<i64>,
) -> PyResult<DynamicOptions<[f64; W]>> {
    let defaults = DynamicOptions::<[f64; W]>::default();
    // Rayleigh damping alpha M + beta K: viscous alpha and stiffness-proportional beta
    let (damping, stiffness_damping) = match rayleigh {
        Some(_) if damping.is_some() || damping_coefficient.is_some() => {
            return Err(InputError::new_err("give rayleigh=(alpha, beta), or damping and damping_coefficient, not both"))
        }
        Some((alpha, beta)) => (Damping::from_keys(Some("viscous"), Some(alpha), defaults.damping).map_err(to_py)?, beta),
        None => (Damping::from_keys(damping, damping_coefficient, defaults.damping).map_err(to_py)?, defaults.stiffness_damping),
    };
    Ok(DynamicOptions {
        duration,
        time_step,
        safety: safety.unwrap_or(defaults.safety),
        damping,
        stiffness_damping,
        initial_displacement: rows_from(initial_displacements, "initial_displacements")?,
        initial_velocity: rows_from(initial_velocities, "initial_velocities")?,
        base_acceleration: series(base_acceleration, "base_acceleration")?,
        base_acceleration_y: series(base_acceleration_y, "base_acceleration_y")?,
        vertical_acceleration: series(vertical_acceleration, "vertical_acceleration")?,
        live_multiplier: live_multiplier.unwrap_or(defaults.live_multiplier),
        record: recording(record_every, record_interval)?,
        large_rotations: large_rotations.unwrap_or(defaults.large_rotations),
        threads: threads.map_or(Ok(defaults.threads), |v| count("threads", v, 0))?,
        contact_update: defaults.contact_update,
    })
}
