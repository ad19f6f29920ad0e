//! What the modal analysis (`crate::modal`) asks of faer: the dense symmetric eigenproblem of its
//! projected matrix, and solves of several right-hand sides in one pass over a Cholesky factor.

use super::*;

/// The eigenvalues (ascending) and orthonormal eigenvectors of a dense symmetric n x n matrix
/// given column-major (its lower triangle is read): the small projected problem of the modal
/// analysis's Lanczos (`crate::modal`). The eigenvectors are returned column-major, column k
/// the vector of eigenvalue k.
pub fn symmetric_eigen(n: usize, a: &[f64]) -> Result<(Vec<f64>, Vec<f64>)> {
    assert_eq!(a.len(), n * n, "symmetric_eigen: a is not n x n");
    if a.iter().any(|v| !v.is_finite()) {
        return Err(Error::Convergence("the projected eigenproblem has a non-finite entry".into()));
    }
    let m = MatRef::from_column_major_slice(a, n, n);
    let evd = faer::linalg::solvers::SelfAdjointEigen::new(m, Side::Lower)
        .map_err(|e| Error::Convergence(format!("the projected eigenproblem did not converge ({e:?})")))?;
    let s = evd.S().column_vector();
    let values = (0..n).map(|k| s[k]).collect();
    let u = evd.U();
    let vectors = (0..n).flat_map(|c| (0..n).map(move |r| u[(r, c)])).collect();
    Ok((values, vectors))
}

impl SparseLu {
    /// Solves A X = B in place for `k` right-hand sides at once (`rhs`: n x k, column-major):
    /// with the Cholesky, one pass over the factor for all of them (the modal analysis's block
    /// Lanczos); with the other factorizations, one column at a time. An error if the matrix is
    /// (numerically) singular.
    pub fn solve_many_in_place(&mut self, rhs: &mut [f64], k: usize) -> Result<()> {
        let n = self.n;
        assert_eq!(rhs.len(), n * k, "solve_many_in_place: rhs is not n x k");
        if self.factorized != Factor::Llt || k <= 1 {
            return rhs.chunks_mut(n.max(1)).try_for_each(|c| self.solve_in_place(c));
        }
        let parts = self.llt.as_mut().unwrap();
        let mut buf = MemBuffer::try_new(parts.symbolic.solve_in_place_scratch::<f64>(k, Par::Seq))
            .map_err(|_| out_of_memory(n, "solve"))?;
        let mut x = vec![0.0; n * k];
        for (xc, mc) in x.chunks_mut(n).zip(rhs.chunks(n)) {
            for (x, &f) in xc.iter_mut().zip(&parts.fwd) {
                *x = mc[f];
            }
        }
        let xm = MatMut::from_column_major_slice_mut(&mut x, n, k);
        LltRef::new(&parts.symbolic, &parts.l_values).solve_in_place_with_conj(Conj::No, xm, Par::Seq, MemStack::new(&mut buf));
        for (xc, mc) in x.chunks(n).zip(rhs.chunks_mut(n)) {
            for (m, &i) in mc.iter_mut().zip(&parts.inv) {
                *m = xc[i];
            }
        }
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(Error::Convergence("the tangent matrix is singular".into()));
        }
        Ok(())
    }
}
