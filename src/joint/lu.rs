//! The small dense LU (1 to 3 unknowns, partial pivoting) of the return mapping's active sets.

/// The factors of the leading k x k block of `g` (k <= 3, overwritten), None if it is
/// singular relative to its scale ([`factor_k`]).
#[inline(always)]
pub(super) fn factor_small(g: &mut [[f64; 3]; 3], k: usize) -> Option<Lu> {
    // one unrolled copy per size: the return mapping eliminates up to 14 sets per plastic update
    match k {
        1 => factor_k::<1>(g),
        2 => factor_k::<2>(g),
        3 => factor_k::<3>(g),
        _ => unreachable!("at most 3 active faces"),
    }
}

/// The factors of a k x k system (k <= 3) by Gaussian elimination with partial pivoting: the
/// row swapped into place at each column, the multipliers, and the eliminated matrix (U on and
/// above its diagonal). Solving with them ([`Lu::apply_k`]) does to the right-hand side the
/// operations of the elimination in their order: the same numbers as eliminating both at once.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Lu {
    pub(super) piv: [u8; 3],
    pub(super) l: [[f64; 3]; 3],
    pub(super) u: [[f64; 3]; 3],
}

/// The factors of the leading K x K block of `g` (overwritten), None if it is singular
/// relative to its scale.
#[inline(always)]
pub(super) fn factor_k<const K: usize>(g: &mut [[f64; 3]; 3]) -> Option<Lu> {
    let mut scale: f64 = 0.0;
    for row in g.iter().take(K) {
        for x in row.iter().take(K) {
            scale = scale.max(x.abs());
        }
    }
    if scale == 0.0 {
        return None;
    }
    let mut lu = Lu::default();
    for col in 0..K {
        // the last row of largest magnitude, as `Iterator::max_by` picks it
        let mut p = col;
        for x in col + 1..K {
            if g[p][col].abs().total_cmp(&g[x][col].abs()) != std::cmp::Ordering::Greater {
                p = x;
            }
        }
        if g[p][col].abs() <= 1e-12 * scale {
            return None;
        }
        g.swap(col, p);
        lu.piv[col] = p as u8;
        for row in col + 1..K {
            let f = g[row][col] / g[col][col];
            let pivot_row = g[col];
            for (x, p) in g[row][col..].iter_mut().zip(&pivot_row[col..]) {
                *x -= f * p;
            }
            lu.l[row][col] = f;
        }
    }
    lu.u = *g;
    Some(lu)
}

impl Lu {
    /// Solves in place with the factors of a K x K system.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // the indices of the elimination in `factor_k`
    pub(super) fn apply_k<const K: usize>(&self, r: &mut [f64; 3]) {
        for col in 0..K {
            r.swap(col, self.piv[col] as usize);
            for row in col + 1..K {
                r[row] -= self.l[row][col] * r[col];
            }
        }
        for col in (0..K).rev() {
            let mut s = r[col];
            for c2 in col + 1..K {
                s -= self.u[col][c2] * r[c2];
            }
            r[col] = s / self.u[col][col];
        }
    }

    /// [`Lu::apply_k`] for a system of size `k`.
    #[inline(always)]
    pub(super) fn apply(&self, r: &mut [f64; 3], k: usize) {
        match k {
            1 => self.apply_k::<1>(r),
            2 => self.apply_k::<2>(r),
            3 => self.apply_k::<3>(r),
            _ => unreachable!("at most 3 active faces"),
        }
    }
}
