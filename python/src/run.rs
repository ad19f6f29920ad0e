//! Running the core from Python: in a thread of its own, Ctrl-C checked meanwhile, the
//! progress callback called, and the exception that stopped a run raised with its results.

use crate::*;

/// A run of the core in a thread of its own, while the calling thread, the GIL released, waits
/// for it and checks for Ctrl-C every [`SIGNAL_POLL`] (Python handles signals in its main thread
/// only). Ctrl-C, or an exception of the user's progress callback, sets `stop`, which the run's
/// monitor sees at its next poll (at most 0.1 s apart, but not within one sparse factorization
/// or ordering: seconds at 10^5 blocks); a run that has not stopped [`GRACE`] after Ctrl-C is
/// left to finish in the background, and the exception is raised without its results.
pub(crate) struct Run {
    pub(crate) progress: Option<Py<PyAny>>,
    pub(crate) raised: Mutex<Option<PyErr>>,
    pub(crate) stop: AtomicBool,
}

/// How often the waiting thread checks for Ctrl-C.
pub(crate) const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// How long the waiting thread waits, after Ctrl-C, for the run's partial results.
pub(crate) const GRACE: Duration = Duration::from_millis(300);

impl Run {
    /// A run reporting to `progress`, refused (InputError naming it) unless it is a callable: it is
    /// checked before the run starts rather than failing at its first report.
    pub(crate) fn new(py: Python<'_>, progress: Option<Py<PyAny>>) -> PyResult<Arc<Run>> {
        if let Some(p) = progress.as_ref().map(|p| p.bind(py)).filter(|p| !p.is_none() && !p.is_callable()) {
            let kind = p.get_type().name().map(|n| n.to_string()).unwrap_or_else(|_| "object".into());
            return Err(InputError::new_err(format!(
                "progress: expected a callable, progress(step, multiplier, displacement, fraction), or None, got {kind} {}",
                p.repr().map(|r| r.to_string()).unwrap_or_default()
            )));
        }
        Ok(Arc::new(Run { progress, raised: Mutex::new(None), stop: AtomicBool::new(false) }))
    }

    /// Keeps the first exception that stops the run.
    pub(crate) fn raise(&self, e: PyErr) {
        let mut slot = self.raised.lock().unwrap_or_else(|p| p.into_inner());
        if slot.is_none() {
            *slot = Some(e);
        }
        self.stop.store(true, Ordering::SeqCst);
    }

    /// The run's monitor: false once stopped; otherwise, unless the call is a poll (a check
    /// within a long step), calls the user's progress callback (taking the GIL).
    pub(crate) fn report(&self, step: usize, multiplier: f64, displacement: f64, fraction: f64, poll: bool) -> bool {
        if self.stop.load(Ordering::SeqCst) {
            return false;
        }
        if poll {
            return true;
        }
        let Some(cb) = &self.progress else { return true };
        Python::attach(|py| match cb.call1(py, (step, multiplier, displacement, fraction)) {
            Ok(_) => true,
            Err(e) => {
                self.raise(e);
                false
            }
        })
    }

    /// Runs `work` in its own thread and waits for it, checking for Ctrl-C; None when it was
    /// left to finish in the background after Ctrl-C.
    pub(crate) fn execute<R: Send + 'static>(
        self: &Arc<Self>,
        py: Python<'_>,
        work: impl FnOnce(Arc<Run>) -> R + Send + 'static,
    ) -> PyResult<Option<R>> {
        let (tx, rx) = mpsc::channel();
        let run = Arc::clone(self);
        std::thread::Builder::new()
            .name("masonry-dem".into())
            .stack_size(64 << 20)
            .spawn(move || {
                let _ = tx.send(work(run));
            })
            .map_err(|e| MasonryError::new_err(format!("cannot start the analysis thread: {e}")))?;
        let this = &**self;
        Ok(py.detach(move || {
            let mut stopped: Option<Instant> = None;
            loop {
                match rx.recv_timeout(SIGNAL_POLL) {
                    Ok(r) => return Some(r),
                    Err(mpsc::RecvTimeoutError::Disconnected) => return None,
                    Err(mpsc::RecvTimeoutError::Timeout) => {}
                }
                match stopped {
                    Some(t) if t.elapsed() >= GRACE => return None,
                    Some(_) => {}
                    None => {
                        if let Some(e) = Python::attach(|py| py.check_signals().err()) {
                            this.raise(e);
                        }
                        if this.stop.load(Ordering::SeqCst) {
                            stopped = Some(Instant::now());
                        }
                    }
                }
            }
        }))
    }

    /// The outcome for Python: the value, or the exception that stopped the run (KeyboardInterrupt
    /// on Ctrl-C, or the progress callback's) with the partial results as its `results`
    /// attribute (None when the run was left to finish in the background).
    pub(crate) fn finish<T>(&self, py: Python<'_>, outcome: Option<PyResult<T>>) -> PyResult<Py<T>>
    where
        T: pyo3::PyClass + Into<pyo3::PyClassInitializer<T>>,
    {
        let raised = self.raised.lock().unwrap_or_else(|p| p.into_inner()).take();
        match (outcome, raised) {
            (Some(Ok(v)), None) => Py::new(py, v),
            (Some(Err(e)), None) => Err(e),
            (None, None) => Err(MasonryError::new_err("internal error (please report it): the analysis thread ended without a result")),
            (outcome, Some(e)) => {
                let partial = match outcome {
                    Some(Ok(v)) => Py::new(py, v)?.into_any(),
                    _ => py.None(),
                };
                // an exception whose instances take no attributes is raised as it is
                let _ = e.value(py).setattr("results", partial);
                Err(e)
            }
        }
    }
}

/// Runs an incremental analysis of `model` (`work`, given the model and the monitor) in a thread
/// of its own ([`Run`]), its progress reported to the user's `progress` callback.
pub(crate) fn analyse<M, T>(
    py: Python<'_>,
    model: &Arc<M>,
    progress: Option<Py<PyAny>>,
    work: impl FnOnce(&M, &mut dyn FnMut(&masonry_dem::analysis::Progress) -> bool) -> Result<T, Error> + Send + 'static,
) -> PyResult<Py<T>>
where
    M: Send + Sync + 'static,
    T: pyo3::PyClass + Into<pyo3::PyClassInitializer<T>> + Send + 'static,
{
    let model = Arc::clone(model);
    let run = Run::new(py, progress)?;
    let res = run.execute(py, move |run| {
        guarded(|| {
            let mut monitor = |p: &masonry_dem::analysis::Progress| run.report(p.step, if p.time.is_nan() { p.multiplier } else { p.time }, p.displacement, p.fraction, p.poll);
            work(&model, &mut monitor)
        })
    })?;
    run.finish(py, res)
}

/// Runs a limit analysis of `model` (of either dimension: `work`, given the model and the monitor)
/// in a thread of its own ([`Run`]): the user's `progress` callback is called after each
/// interior-point iteration, the iterations counted over all the programs. Stopped by Ctrl-C or by
/// the callback, an unfinished program certifies nothing: the partial result, `interrupted(model,
/// start)`, holds no multiplier (attached to the exception that stopped it).
pub(crate) fn limit_run<M, V>(
    py: Python<'_>,
    model: &Arc<M>,
    progress: Option<Py<PyAny>>,
    work: impl FnOnce(&M, &mut dyn FnMut(&limit::LimitProgress) -> bool) -> Result<Results<V>, Error> + Send + 'static,
    interrupted: fn(&M, Instant) -> Results<V>,
) -> PyResult<Py<PyResults>>
where
    M: Send + Sync + 'static,
    V: Send + 'static,
    PyResults: From<Results<V>>,
{
    let model = Arc::clone(model);
    let run = Run::new(py, progress)?;
    let start = Instant::now();
    let res = run.execute(py, move |run| {
        guarded(|| {
            let mut count = 0usize;
            let mut monitor = |p: &limit::LimitProgress| {
                count += 1;
                run.report(count, p.multiplier, f64::NAN, f64::NAN, false)
            };
            match work(&model, &mut monitor) {
                Err(Error::Interrupted) => Ok(interrupted(&model, start)),
                r => r,
            }
            .map(PyResults::from)
        })
    })?;
    run.finish(py, res)
}
