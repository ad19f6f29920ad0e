//! The only module that calls faer: a square sparse matrix of fixed pattern, assembled by
//! value slots, factorized by sparse LU (the tangent is non-symmetric with non-associative
//! flow). The symbolic analysis (fill-reducing ordering) is done once, when the pattern is
//! built; each `factorize` is a numeric refactorization into preallocated buffers.

use crate::error::{Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::mat::MatMut;
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuRef, NumericLu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, Par};

/// A sparse square matrix with a fixed pattern and its LU factorization.
pub struct SparseLu {
    n: usize,
    pattern: SymbolicSparseColMat<usize>,
    values: Vec<f64>,
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, f64>,
    factor_buf: MemBuffer,
    solve_buf: MemBuffer,
    factorized: bool,
}

impl SparseLu {
    /// Builds the pattern from (row, column) entries (duplicates allowed) of an n x n matrix
    /// and runs the symbolic analysis. Every diagonal entry is part of the pattern.
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
        let symbolic =
            factorize_symbolic_lu(pattern.as_ref(), Default::default()).map_err(|e| {
                Error::Convergence(format!("sparse LU symbolic analysis failed: {e:?}"))
            })?;
        let par = Par::Seq;
        let factor_buf = MemBuffer::try_new(
            symbolic.factorize_numeric_lu_scratch::<f64>(par, Default::default()),
        )
        .map_err(|_| {
            Error::input(format!(
                "out of memory for the factorization of a {n} x {n} matrix"
            ))
        })?;
        let solve_buf = MemBuffer::try_new(symbolic.solve_in_place_scratch::<f64>(1, par))
            .map_err(|_| {
                Error::input(format!("out of memory for the solve of a {n} x {n} matrix"))
            })?;
        Ok(SparseLu {
            n,
            pattern,
            values: vec![0.0; nnz],
            symbolic,
            numeric: NumericLu::new(),
            factor_buf,
            solve_buf,
            factorized: false,
        })
    }

    /// The value slot of entry (row, col), if it is in the pattern.
    pub fn slot(&self, row: usize, col: usize) -> Option<usize> {
        let p = self.pattern.as_ref();
        let start = p.col_ptr()[col];
        let rows = &p.row_idx()[start..p.col_ptr()[col + 1]];
        rows.binary_search(&row).ok().map(|k| start + k)
    }

    /// The values, in slot order; zero them and add contributions before `factorize`.
    pub fn values_mut(&mut self) -> &mut [f64] {
        self.factorized = false;
        &mut self.values
    }

    /// Numeric LU of the current values (partial pivoting), reusing the symbolic analysis.
    pub fn factorize(&mut self) -> Result<()> {
        if self.values.iter().any(|v| !v.is_finite()) {
            return Err(Error::Convergence(
                "the tangent matrix has a non-finite entry".into(),
            ));
        }
        let mat = SparseColMatRef::new(self.pattern.as_ref(), &self.values);
        self.symbolic
            .factorize_numeric_lu(
                &mut self.numeric,
                mat,
                Par::Seq,
                MemStack::new(&mut self.factor_buf),
                Default::default(),
            )
            .map_err(|e| Error::Convergence(format!("the tangent matrix is singular ({e:?})")))?;
        self.factorized = true;
        Ok(())
    }

    /// Solves A x = rhs in place; an error if the matrix is (numerically) singular.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<()> {
        assert!(self.factorized, "factorize before solve");
        let lu = LuRef::new_unchecked(&self.symbolic, &self.numeric);
        let m = MatMut::from_column_major_slice_mut(rhs, self.n, 1);
        lu.solve_in_place_with_conj(Conj::No, m, Par::Seq, MemStack::new(&mut self.solve_buf));
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(Error::Convergence("the tangent matrix is singular".into()));
        }
        Ok(())
    }
}
