//! The only module that calls faer: a square sparse matrix of fixed pattern, assembled by
//! value slots and factorized. A symmetric matrix (associative flow, load control) goes to a
//! sparse Cholesky LL^T with an AMD ordering (METIS's nested dissection from
//! [`NESTED_DISSECTION_MIN`] equations), about 10 times faster than faer's LU with its own
//! choice of method here (n = 3,120: 2.5 ms against 26 ms; n = 30,150: 94 ms against 521 ms); a
//! non-symmetric one (non-associative flow, the bordered system of displacement control), or one
//! that is not positive definite (softening), to a supernodal sparse LU, or to a dense LU with
//! partial pivoting up to [`DENSE_LU_MAX`] equations. The limit analysis's normal equations,
//! symmetric and semi-definite, go to an LDL^T on the Cholesky's analysis. Each symbolic
//! analysis is done once, when first needed; each `factorize` is a numeric refactorization into
//! preallocated buffers. The modal analysis's small dense symmetric eigenproblem is solved here
//! too ([`symmetric_eigen`]), and its solves of several right-hand sides at once, in `eigen`.

use crate::error::{Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::{factor::lu_in_place, factor::lu_in_place_scratch, solve::solve_in_place_scratch as dense_solve_scratch, solve::solve_in_place_with_conj as dense_solve};
use faer::mat::{MatMut, MatRef};
use faer::perm::PermRef;
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LdltRef, LltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::utils::permute_self_adjoint_to_unsorted;
use faer::dyn_stack::StackReq;
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuRef, LuSymbolicParams, NumericLu, SymbolicLu};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat, SymbolicSparseColMatRef};
use faer::{Conj, Par, Side};

mod eigen;
pub use eigen::symmetric_eigen;

/// A sparse square matrix with a fixed pattern and its factorization.
pub struct SparseLu {
    n: usize,
    pattern: SymbolicSparseColMat<usize>,
    values: Vec<f64>,
    /// the slots of every pair of transposed entries off the diagonal, each pair once (None:
    /// the pattern is not symmetric)
    transpose: Option<Vec<(u32, u32)>>,
    lu: Option<LuParts>,
    llt: Option<LltParts>,
    dense: Option<DenseParts>,
    factorized: Factor,
    /// the Cholesky orders by nested dissection from this many equations
    nested_dissection_min: usize,
}

/// From this many equations the Cholesky's fill-reducing ordering is METIS's nested dissection
/// instead of faer's AMD. Numeric factorizations of a running-bond wall's elastic stiffness,
/// medians of 7 after the symbolic analysis, two alternate runs each (busy machine), AMD against
/// nested dissection: 3,120 equations 2.3 / 3.2 ms against 3.7 / 5.1 ms; 30,150: 52 / 52 ms
/// against 62 / 51 ms (factor 3.57 M against 2.92 M values); 100,743: 327 / 320 ms against
/// 259 / 341 ms (12.9 M against 11.7 M); 200,079: 849 / 875 ms against 637 / 779 ms (35.4 M
/// against 25.4 M); 300,042: 1.85 / 1.76 s against 1.40 / 1.13 s (53.8 M against 40.5 M).
const NESTED_DISSECTION_MIN: usize = 150_000;

/// An LDL^T pivot that rounding made exactly zero is replaced by this: the component of the
/// solution along it comes out zero, as for a dependent row (Wright, "Modified Cholesky
/// factorizations in interior-point algorithms for linear programming", 1999). Failing there and
/// going to an LU instead left 32 of 1,000 textured 33-block walls short of the interior
/// point's tolerance (the LU's directions no better); with it, two.
const ZERO_PIVOT_REPLACEMENT: f64 = 1e128;

/// Up to this many equations a non-symmetric matrix is factorized dense (LU with partial
/// pivoting). faer's simplicial sparse LU took 56% of a 33-block wall's analysis with psi = 0
/// (96 equations). Whole analyses to collapse, best of 20 runs side by side: 33 blocks 30 ms
/// sparse against 17 ms dense, 55 blocks (165 equations) 210 ms against 130 ms; at 110 blocks
/// (330 equations) the dense LU was the slower, 1.42 s against 1.04 s.
const DENSE_LU_MAX: usize = 200;

struct DenseParts {
    /// the matrix, column-major, overwritten by its factors L (unit lower) and U
    a: Vec<f64>,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
    factor_buf: MemBuffer,
    solve_buf: MemBuffer,
}

struct LuParts {
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, f64>,
    factor_buf: MemBuffer,
    solve_buf: MemBuffer,
}

/// The Cholesky of the matrix permuted once, at the symbolic analysis: faer's numeric
/// factorization, given the ordering, would permute the matrix again at every call (4% of a
/// 33-block wall's analysis), and its solve the right-hand side.
struct LltParts {
    symbolic: SymbolicCholesky<usize>,
    /// the permuted triangle that the factorization reads (`side`), and the slot of the
    /// pattern each of its values comes from
    permuted: SymbolicSparseColMat<usize>,
    side: Side,
    src: Vec<usize>,
    permuted_values: Vec<f64>,
    /// the fill-reducing ordering (entry i of the permuted matrix is entry `fwd[i]`) and its
    /// inverse
    fwd: Vec<usize>,
    inv: Vec<usize>,
    /// the permuted right-hand sides of a solve
    x: Vec<f64>,
    l_values: Vec<f64>,
    factor_buf: MemBuffer,
    /// the scratch of a solve of `solve_cols` right-hand sides at once
    solve_buf: MemBuffer,
    solve_cols: usize,
    /// the scratch of an LDL^T factorization on the same analysis, once one is asked for
    ldlt_buf: Option<MemBuffer>,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Factor {
    None,
    Lu,
    Llt,
    Ldlt,
    Dense,
}

/// The value slot of entry (row, col) of a pattern with sorted row indices, if it is there.
fn slot_of(p: SymbolicSparseColMatRef<'_, usize>, row: usize, col: usize) -> Option<usize> {
    let start = p.col_ptr()[col];
    let rows = &p.row_idx()[start..p.col_ptr()[col + 1]];
    rows.binary_search(&row).ok().map(|k| start + k)
}

fn out_of_memory(n: usize, what: &str) -> Error {
    Error::input(format!("out of memory for the {what} of a {n} x {n} matrix"))
}

impl SparseLu {
    /// Builds the pattern from (row, column) entries (duplicates allowed) of an n x n matrix.
    /// Every diagonal entry is part of the pattern.
    pub fn new(n: usize, entries: impl IntoIterator<Item = (usize, usize)>) -> Result<Self> {
        let mut cols: Vec<Vec<usize>> = vec![vec![]; n];
        for (i, c) in cols.iter_mut().enumerate() {
            c.push(i);
        }
        for (r, c) in entries {
            debug_assert!(r < n && c < n);
            cols[c].push(r);
        }
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::new();
        col_ptr.push(0);
        for c in cols.iter_mut() {
            c.sort_unstable();
            c.dedup();
            row_idx.extend_from_slice(c);
            col_ptr.push(row_idx.len());
        }
        let nnz = row_idx.len();
        let pattern = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        // the slots of the transposed pairs; None if the pattern is not symmetric (or has more
        // slots than 32 bits index, where a matrix could not be factorized anyway)
        let p = pattern.as_ref();
        let transpose = (0..n)
            .flat_map(|c| (p.col_ptr()[c]..p.col_ptr()[c + 1]).map(move |s| (s, p.row_idx()[s], c)))
            .filter(|&(_, r, c)| r > c)
            .map(|(s, r, c)| Some((u32::try_from(s).ok()?, u32::try_from(slot_of(p, c, r)?).ok()?)))
            .collect();
        let this = SparseLu {
            n,
            pattern,
            values: vec![0.0; nnz],
            transpose,
            lu: None,
            llt: None,
            dense: None,
            factorized: Factor::None,
            nested_dissection_min: NESTED_DISSECTION_MIN,
        };
        Ok(this)
    }

    /// The LU's symbolic analysis and buffers, made on first use. Supernodal whatever the
    /// pattern: faer's own choice took the simplicial LU on these matrices, and whole analyses
    /// of psi = 0 walls to collapse ran 1.7-2.6 times slower with it (best of one run each, side
    /// by side: 69 blocks 0.152 s against 0.091 s, 151 blocks 1.38 s against 0.52 s, 265 blocks
    /// 17.0 s against 7.0 s, the same steps and iterations).
    fn ensure_lu(&mut self) -> Result<()> {
        if self.lu.is_none() {
            let n = self.n;
            let symbolic = factorize_symbolic_lu(
                self.pattern.as_ref(),
                LuSymbolicParams { supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL, ..Default::default() },
            ).map_err(|e| {
                Error::Convergence(format!("sparse LU symbolic analysis failed: {e:?}"))
            })?;
            let factor_buf =
                MemBuffer::try_new(symbolic.factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default()))
                    .map_err(|_| out_of_memory(n, "factorization"))?;
            let solve_buf = MemBuffer::try_new(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq))
                .map_err(|_| out_of_memory(n, "solve"))?;
            self.lu = Some(LuParts { symbolic, numeric: NumericLu::new(), factor_buf, solve_buf });
        }
        Ok(())
    }

    /// The Cholesky's lower-triangle pattern, symbolic analysis and buffers, made on first use.
    fn ensure_llt(&mut self) -> Result<()> {
        if self.llt.is_none() {
            let n = self.n;
            let p = self.pattern.as_ref();
            let mut col_ptr = Vec::with_capacity(n + 1);
            let mut row_idx = vec![];
            let mut lower_src = vec![];
            col_ptr.push(0);
            for c in 0..n {
                for s in p.col_ptr()[c]..p.col_ptr()[c + 1] {
                    if p.row_idx()[s] >= c {
                        row_idx.push(p.row_idx()[s]);
                        lower_src.push(s);
                    }
                }
                col_ptr.push(row_idx.len());
            }
            let lower = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
            let nd = if n >= self.nested_dissection_min { nested_dissection(p) } else { None };
            let ordering = match &nd {
                Some((perm, inv)) => SymmetricOrdering::Custom(PermRef::new_checked(perm, inv, n)),
                None => SymmetricOrdering::Amd,
            };
            let failed = |e: faer::sparse::FaerError| Error::Convergence(format!("sparse Cholesky symbolic analysis failed: {e:?}"));
            let ordered = factorize_symbolic_cholesky(lower.as_ref(), Side::Lower, ordering, CholeskySymbolicParams::default())
                .map_err(failed)?;
            // the matrix permuted as faer's factorization would permute it (the same function:
            // the same entries in the same order, so the same factors bit for bit), once, with
            // each value's source slot carried in place of the value
            let simplicial = matches!(ordered.raw(), SymbolicCholeskyRaw::Simplicial(_));
            let side = if simplicial { Side::Upper } else { Side::Lower };
            let (fwd, inv): (Vec<usize>, Vec<usize>) = match ordered.perm() {
                Some(p) => (p.arrays().0.to_vec(), p.arrays().1.to_vec()),
                None => ((0..n).collect(), (0..n).collect()),
            };
            // `to`: the lower triangle permuted into triangle `to`, with each value's source
            // slot in place of the value
            let slots: Vec<f64> = lower_src.iter().map(|&s| s as f64).collect();
            let permute = |to: Side| -> Result<(SymbolicSparseColMat<usize>, Vec<usize>)> {
                let nnz = slots.len();
                let (mut val, mut col_ptr, mut row_idx) = (vec![0.0; nnz], vec![0usize; n + 1], vec![0usize; nnz]);
                let mut buf = MemBuffer::try_new(StackReq::new::<usize>(n)).map_err(|_| out_of_memory(n, "ordering"))?;
                permute_self_adjoint_to_unsorted(
                    &mut val,
                    &mut col_ptr,
                    &mut row_idx,
                    SparseColMatRef::new(lower.as_ref(), &slots),
                    PermRef::new_checked(&fwd, &inv, n),
                    Side::Lower,
                    to,
                    MemStack::new(&mut buf),
                );
                let kept = col_ptr[n];
                row_idx.truncate(kept);
                let src = val[..kept].iter().map(|&v| v as usize).collect();
                Ok((SymbolicSparseColMat::new_unsorted_checked(n, n, col_ptr, None, row_idx), src))
            };
            let (permuted, src) = permute(side)?;
            // the same analysis of the permuted matrix, with faer's choice of method above;
            // with the identity ordering faer analyses the upper triangle as given
            let upper = if side == Side::Upper { None } else { Some(permute(Side::Upper)?.0) };
            let threshold = if simplicial { SupernodalThreshold::FORCE_SIMPLICIAL } else { SupernodalThreshold::FORCE_SUPERNODAL };
            let symbolic = factorize_symbolic_cholesky(
                upper.as_ref().unwrap_or(&permuted).as_ref(),
                Side::Upper,
                SymmetricOrdering::Identity,
                CholeskySymbolicParams { supernodal_flop_ratio_threshold: threshold, ..Default::default() },
            )
            .map_err(failed)?;
            let factor_buf =
                MemBuffer::try_new(symbolic.factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default()))
                    .map_err(|_| out_of_memory(n, "factorization"))?;
            let solve_buf = MemBuffer::try_new(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq))
                .map_err(|_| out_of_memory(n, "solve"))?;
            let l_values = vec![0.0; symbolic.len_val()];
            let permuted_values = vec![0.0; src.len()];
            self.llt = Some(LltParts { symbolic, permuted, side, src, permuted_values, fwd, inv, x: vec![0.0; n], l_values, factor_buf, solve_buf, solve_cols: 1, ldlt_buf: None });
        }
        Ok(())
    }

    /// Whether the values are symmetric to round-off: each pair within 1e-12 of the largest
    /// entry (assembly leaves entries that cancel at about 1e-16 of it, on one side only);
    /// `largest`: the largest magnitude of the values.
    fn symmetric(&self, largest: f64) -> bool {
        match &self.transpose {
            None => false,
            Some(t) => {
                let (v, tol) = (&self.values, 1e-12 * largest);
                t.iter().all(|&(s, ts)| (v[s as usize] - v[ts as usize]).abs() <= tol)
            }
        }
    }

    /// Whether the current values are factorized (and `solve_in_place` may be called).
    pub fn is_factorized(&self) -> bool {
        self.factorized != Factor::None
    }

    /// The first value slot of column `col` (the values are stored column by column; `col = n`
    /// gives the number of values).
    pub fn column_start(&self, col: usize) -> usize {
        self.pattern.col_ptr()[col]
    }

    /// The value slot of entry (row, col), if it is in the pattern.
    pub fn slot(&self, row: usize, col: usize) -> Option<usize> {
        slot_of(self.pattern.as_ref(), row, col)
    }

    /// The values, in slot order; zero them and add contributions before `factorize`.
    pub fn values_mut(&mut self) -> &mut [f64] {
        self.factorized = Factor::None;
        &mut self.values
    }

    /// Factorizes the current values: Cholesky if they are symmetric and positive definite,
    /// else LU with partial pivoting; each reuses its symbolic analysis.
    pub fn factorize(&mut self) -> Result<()> {
        // the largest magnitude, and whether every value is finite, in one pass
        let (largest, finite) = self.values.iter().fold((0.0_f64, true), |(m, ok), v| (m.max(v.abs()), ok && v.is_finite()));
        if !finite {
            return Err(Error::Convergence(
                "the tangent matrix has a non-finite entry".into(),
            ));
        }
        self.factorized = Factor::None;
        if self.symmetric(largest) && self.factorize_llt()? {
            return Ok(());
        }
        if self.n <= DENSE_LU_MAX {
            return self.factorize_dense();
        }
        self.ensure_lu()?;
        let parts = self.lu.as_mut().unwrap();
        let mat = SparseColMatRef::new(self.pattern.as_ref(), &self.values);
        let r = parts
            .symbolic
            .factorize_numeric_lu(
                &mut parts.numeric,
                mat,
                Par::Seq,
                MemStack::new(&mut parts.factor_buf),
                Default::default(),
            )
            .map(|_| ())
            .map_err(|e| Error::Convergence(format!("the tangent matrix is singular ({e:?})")));
        r?;
        self.factorized = Factor::Lu;
        Ok(())
    }

    /// The sparse LDL^T of the current values, on the Cholesky's symbolic analysis, without
    /// pivoting: for a symmetric matrix that is positive semi-definite in exact arithmetic but
    /// on which rounding made a Cholesky pivot non-positive (an interior point's normal
    /// equations near the optimum); a tiny pivot of either sign is kept as it is, a zero one
    /// replaced by [`ZERO_PIVOT_REPLACEMENT`], and the caller corrects what it solves. An error
    /// for non-finite values.
    pub fn factorize_ldlt(&mut self) -> Result<()> {
        if self.values.iter().any(|v| !v.is_finite()) {
            return Err(Error::Convergence("the matrix has a non-finite entry".into()));
        }
        self.factorized = Factor::None;
        let n = self.n;
        let parts = self.permuted_parts()?;
        if parts.ldlt_buf.is_none() {
            let req = parts.symbolic.factorize_numeric_ldlt_scratch::<f64>(Par::Seq, Default::default());
            parts.ldlt_buf = Some(MemBuffer::try_new(req).map_err(|_| out_of_memory(n, "factorization"))?);
        }
        let mat = SparseColMatRef::new(parts.permuted.as_ref(), &parts.permuted_values);
        // a zero pivot (a row that depends on those before it, to rounding) becomes a huge
        // one, which sets that component of the solution to zero instead of failing
        let reg = LdltRegularization {
            dynamic_regularization_signs: None,
            dynamic_regularization_delta: ZERO_PIVOT_REPLACEMENT,
            dynamic_regularization_epsilon: f64::MIN_POSITIVE,
        };
        parts
            .symbolic
            .factorize_numeric_ldlt(
                &mut parts.l_values,
                mat,
                parts.side,
                reg,
                Par::Seq,
                MemStack::new(parts.ldlt_buf.as_mut().unwrap()),
                Default::default(),
            )
            .map_err(|e| Error::Convergence(format!("the LDL^T factorization failed ({e:?})")))?;
        self.factorized = Factor::Ldlt;
        Ok(())
    }

    /// The numeric Cholesky of the current values (the symbolic analysis done once); false if
    /// a pivot is not positive.
    fn factorize_llt(&mut self) -> Result<bool> {
        let parts = self.permuted_parts()?;
        let mat = SparseColMatRef::new(parts.permuted.as_ref(), &parts.permuted_values);
        let ok = parts
            .symbolic
            .factorize_numeric_llt(
                &mut parts.l_values,
                mat,
                parts.side,
                LltRegularization::default(),
                Par::Seq,
                MemStack::new(&mut parts.factor_buf),
                Default::default(),
            )
            .is_ok();
        if ok {
            self.factorized = Factor::Llt;
        }
        Ok(ok)
    }

    /// The Cholesky's parts (analysed once) with the current values permuted into them.
    fn permuted_parts(&mut self) -> Result<&mut LltParts> {
        self.ensure_llt()?;
        let parts = self.llt.as_mut().unwrap();
        for (v, &s) in parts.permuted_values.iter_mut().zip(&parts.src) {
            *v = self.values[s];
        }
        Ok(parts)
    }

    /// The dense LU with partial pivoting of a small non-symmetric matrix (a zero pivot shows
    /// as a non-finite solution, which [`SparseLu::solve_in_place`] reports as singular).
    fn factorize_dense(&mut self) -> Result<()> {
        let n = self.n;
        if self.dense.is_none() {
            let factor_buf = MemBuffer::try_new(lu_in_place_scratch::<usize, f64>(n, n, Par::Seq, Default::default()))
                .map_err(|_| out_of_memory(n, "factorization"))?;
            let solve_buf = MemBuffer::try_new(dense_solve_scratch::<usize, f64>(n, 1, Par::Seq))
                .map_err(|_| out_of_memory(n, "solve"))?;
            self.dense = Some(DenseParts { a: vec![0.0; n * n], perm: vec![0; n], perm_inv: vec![0; n], factor_buf, solve_buf });
        }
        let parts = self.dense.as_mut().unwrap();
        parts.a.fill(0.0);
        let p = self.pattern.as_ref();
        for c in 0..n {
            for s in p.col_ptr()[c]..p.col_ptr()[c + 1] {
                parts.a[c * n + p.row_idx()[s]] = self.values[s];
            }
        }
        let a = MatMut::from_column_major_slice_mut(&mut parts.a, n, n);
        lu_in_place(a, &mut parts.perm, &mut parts.perm_inv, Par::Seq, MemStack::new(&mut parts.factor_buf), Default::default());
        self.factorized = Factor::Dense;
        Ok(())
    }

    /// Solves A x = rhs in place; an error if the matrix is (numerically) singular.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<()> {
        self.solve_columns_in_place(rhs, 1)
    }

    /// Solves A X = B in place for the `k` columns of `rhs` (one after the other, n values each):
    /// with a Cholesky or an LDL^T in one pass over the factor for all of them (a solve streams
    /// the factor from memory: at 56,000 equations two columns take 1.2 times as long as one),
    /// otherwise a column at a time. An error if the matrix is (numerically) singular or out of
    /// memory for the solve's scratch.
    pub fn solve_columns_in_place(&mut self, rhs: &mut [f64], k: usize) -> Result<()> {
        let n = self.n;
        assert_eq!(rhs.len(), n * k, "k columns of n values");
        if n == 0 {
            return Ok(());
        }
        match self.factorized {
            Factor::None => panic!("factorize before solve"),
            Factor::Lu => {
                let parts = self.lu.as_mut().unwrap();
                let lu = LuRef::new_unchecked(&parts.symbolic, &parts.numeric);
                for col in rhs.chunks_exact_mut(n) {
                    let m = MatMut::from_column_major_slice_mut(col, n, 1);
                    lu.solve_in_place_with_conj(Conj::No, m, Par::Seq, MemStack::new(&mut parts.solve_buf));
                }
            }
            Factor::Dense => {
                let parts = self.dense.as_mut().unwrap();
                let lu = MatRef::from_column_major_slice(&parts.a, n, n);
                let perm = PermRef::new_checked(&parts.perm, &parts.perm_inv, n);
                for col in rhs.chunks_exact_mut(n) {
                    let m = MatMut::from_column_major_slice_mut(col, n, 1);
                    dense_solve(lu, lu, perm, Conj::No, m, Par::Seq, MemStack::new(&mut parts.solve_buf));
                }
            }
            Factor::Llt | Factor::Ldlt => {
                let parts = self.llt.as_mut().unwrap();
                if k > parts.solve_cols {
                    parts.solve_buf = MemBuffer::try_new(parts.symbolic.solve_in_place_scratch::<f64>(k, Par::Seq))
                        .map_err(|_| out_of_memory(n, "solve"))?;
                    parts.solve_cols = k;
                }
                // permuted, solved and permuted back as faer's solve would (copies only)
                parts.x.resize(n * k, 0.0);
                for (x, m) in parts.x.chunks_exact_mut(n).zip(rhs.chunks_exact(n)) {
                    for (x, &f) in x.iter_mut().zip(&parts.fwd) {
                        *x = m[f];
                    }
                }
                let xm = MatMut::from_column_major_slice_mut(&mut parts.x[..n * k], n, k);
                let stack = MemStack::new(&mut parts.solve_buf);
                if self.factorized == Factor::Llt {
                    LltRef::new(&parts.symbolic, &parts.l_values).solve_in_place_with_conj(Conj::No, xm, Par::Seq, stack);
                } else {
                    LdltRef::new(&parts.symbolic, &parts.l_values).solve_in_place_with_conj(Conj::No, xm, Par::Seq, stack);
                }
                for (m, x) in rhs.chunks_exact_mut(n).zip(parts.x.chunks_exact(n)) {
                    for (m, &i) in m.iter_mut().zip(&parts.inv) {
                        *m = x[i];
                    }
                }
            }
        }
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(Error::Convergence("the tangent matrix is singular".into()));
        }
        Ok(())
    }
}

/// METIS's nested-dissection ordering of a symmetric pattern (diagonal ignored): the
/// permutation and its inverse in faer's convention (entry i of the reordered matrix is entry
/// `perm[i]` of the original). None if the pattern is too large for METIS's 32-bit indices or
/// METIS fails; the caller then keeps AMD.
fn nested_dissection(p: SymbolicSparseColMatRef<'_, usize>) -> Option<(Vec<usize>, Vec<usize>)> {
    let n = p.ncols();
    let mut xadj: Vec<i32> = Vec::with_capacity(n + 1);
    let mut adjncy: Vec<i32> = Vec::with_capacity(p.row_idx().len());
    xadj.push(0);
    for c in 0..n {
        for &r in &p.row_idx()[p.col_ptr()[c]..p.col_ptr()[c + 1]] {
            if r != c {
                adjncy.push(i32::try_from(r).ok()?);
            }
        }
        xadj.push(i32::try_from(adjncy.len()).ok()?);
    }
    let mut nvtxs = i32::try_from(n).ok()?;
    let (mut perm, mut iperm) = (vec![0i32; n], vec![0i32; n]);
    // SAFETY: METIS reads `nvtxs` vertices from the CSR arrays `xadj` (n + 1 entries) and
    // `adjncy` (xadj[n] entries), whose indices are in 0..n, writes n entries into each of
    // `perm` and `iperm`, and takes null for the optional weights and options (defaults).
    let status = unsafe {
        metis_sys::METIS_NodeND(
            &mut nvtxs,
            xadj.as_mut_ptr(),
            adjncy.as_mut_ptr(),
            std::ptr::null_mut(),
            std::ptr::null_mut(),
            perm.as_mut_ptr(),
            iperm.as_mut_ptr(),
        )
    };
    if status != metis_sys::rstatus_et_METIS_OK {
        return None;
    }
    let to_usize = |v: Vec<i32>| v.into_iter().map(usize::try_from).collect::<std::result::Result<Vec<_>, _>>().ok();
    let (perm, iperm) = (to_usize(perm)?, to_usize(iperm)?);
    // a permutation and its inverse, or nothing
    (perm.iter().enumerate().all(|(i, &k)| k < n && iperm[k] == i)).then_some((perm, iperm))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 5-point Laplacian on an m x m grid plus the identity (symmetric positive definite).
    fn grid(m: usize) -> SparseLu {
        let n = m * m;
        let id = |i: usize, j: usize| i * m + j;
        let mut entries = vec![];
        for i in 0..m {
            for j in 0..m {
                if i + 1 < m {
                    entries.extend([(id(i, j), id(i + 1, j)), (id(i + 1, j), id(i, j))]);
                }
                if j + 1 < m {
                    entries.extend([(id(i, j), id(i, j + 1)), (id(i, j + 1), id(i, j))]);
                }
            }
        }
        let mut a = SparseLu::new(n, entries.clone()).unwrap();
        for (r, c) in entries {
            let s = a.slot(r, c).unwrap();
            a.values_mut()[s] = -1.0;
        }
        for k in 0..n {
            let s = a.slot(k, k).unwrap();
            a.values_mut()[s] = 5.0;
        }
        a
    }

    #[test]
    fn nested_dissection_is_a_permutation_with_less_fill_and_the_same_solution() {
        let m = 60;
        let (mut amd, mut nd) = (grid(m), grid(m));
        nd.nested_dissection_min = 0;
        let (perm, iperm) = nested_dissection(nd.pattern.as_ref()).unwrap();
        let mut seen = vec![false; m * m];
        for (i, &k) in perm.iter().enumerate() {
            assert!(!seen[k] && iperm[k] == i);
            seen[k] = true;
        }
        let rhs: Vec<f64> = (0..m * m).map(|k| (k as f64 * 0.37).sin()).collect();
        let (mut x_amd, mut x_nd) = (rhs.clone(), rhs.clone());
        amd.factorize().unwrap();
        nd.factorize().unwrap();
        assert!(amd.factorized == Factor::Llt && nd.factorized == Factor::Llt);
        amd.solve_in_place(&mut x_amd).unwrap();
        nd.solve_in_place(&mut x_nd).unwrap();
        // nested dissection's fill on a 2D grid is O(n log n), below AMD's at this size
        let fill = |a: &SparseLu| a.llt.as_ref().unwrap().symbolic.len_val();
        assert!(fill(&nd) < fill(&amd), "fill {} against {}", fill(&nd), fill(&amd));
        let err = x_amd.iter().zip(&x_nd).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        assert!(err < 1e-12, "solutions differ by {err}");
    }
}
