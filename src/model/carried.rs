//! Loads carried by blocks: a floor's or a roof's reaction, or a backfill's weight, resting at a
//! point of a wall block, whose mass moves with the block. The plane's model and the 3D model
//! lump them the same way: each block's mass takes the loads' masses `W / g`, its centre of mass
//! (where its dofs are) moves to the centre of the block's and the loads' masses together, and
//! its rotary inertia about that point takes the parallel-axis terms of both. The weights then
//! act at the dofs, so the dead load (the weights along gravity), the horizontal live load
//! (lambda times the weights), a ground motion's inertial forces and the masses of the explicit
//! solver and of modal analysis take the loads with no term of their own.

use crate::error::{Error, Result};

/// A vertical dead load `weight` \[N\] resting at `point` \[m\] of wall block `block` (an index
/// into the spec's blocks), with its mass `weight / g`: it takes the horizontal live load in
/// proportion to its weight and moves with the block in the explicit solver and modal analysis
/// (a point mass at `point`). `D` is 2 in the plane (x, y) and 3 in 3D (x, y, z).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CarriedLoad<const D: usize = 2> {
    /// The wall block that carries it (0-based, among the spec's blocks).
    pub block: usize,
    /// Where it rests \[m\]: inside the block (on its boundary within the contact tolerance).
    pub point: [f64; D],
    /// Its weight \[N\], finite and not negative.
    pub weight: f64,
}

/// The case file's key of load `k`: "loads.carried\[k\]".
pub(crate) fn key(k: usize) -> String {
    format!("loads.carried[{k}]")
}

/// The checks of each load alone: a wall block (not a support, the base or the top beam), a
/// finite point, a finite weight not negative, and gravity to give it a mass.
pub(crate) fn check<const D: usize>(loads: &[CarriedLoad<D>], n_wall: usize, gravity: f64) -> Result<()> {
    for (k, l) in loads.iter().enumerate() {
        let refuse = |why: String| Err(Error::input_at(key(k), format!("{}: {why}", key(k))));
        if l.block >= n_wall {
            return refuse(format!(
                "block {} is not a wall block (the wall has {n_wall}, numbered from 0; supports, the base and the top beam carry no load)",
                l.block
            ));
        }
        if !l.point.iter().all(|v| v.is_finite()) {
            return refuse(format!("point {:?} must be finite", l.point));
        }
        if !(l.weight.is_finite() && l.weight >= 0.0) {
            return refuse(format!("weight must be finite and not negative, got {} N", l.weight));
        }
        if !(gravity > 0.0) && l.weight > 0.0 {
            return refuse("a carried load needs gravity > 0 (its mass is its weight over g)".into());
        }
    }
    Ok(())
}

/// Refuses a load whose point lies outside its block by more than `tol` \[m\]: `outside(i, p)`
/// says by how much point `p` lies outside block `i` (0 or less inside), `name(i)` names it.
pub(crate) fn check_inside<const D: usize>(
    loads: &[CarriedLoad<D>],
    tol: f64,
    outside: impl Fn(usize, [f64; D]) -> f64,
    name: impl Fn(usize) -> String,
) -> Result<()> {
    for (k, l) in loads.iter().enumerate() {
        let d = outside(l.block, l.point);
        if !(d <= tol) {
            return Err(Error::input_at(
                key(k),
                format!(
                    "{}: point {:?} lies {d:.3e} m outside {}, beyond the contact tolerance ({tol:.1e} m): a carried load rests on its block",
                    key(k),
                    l.point,
                    name(l.block)
                ),
            ));
        }
    }
    Ok(())
}

/// Lumps the loads' masses into their blocks: each loaded block's `mass` takes `W / g` and its
/// `centre` (its centre of mass, the block's own on entry) moves to that of the block and its
/// loads together. Returns, for each loaded block, the second moments `S = sum m r r^T` of the
/// block's own mass (at its old centre) and of the loads' about the new centre \[kg m2\]: the
/// parallel-axis terms (the plane's polar moment takes `trace S`, a 3D inertia tensor
/// `trace S I - S`). No loads, no change.
pub(crate) fn lump<const D: usize>(
    loads: &[CarriedLoad<D>],
    gravity: f64,
    mass: &mut [f64],
    centre: &mut [[f64; D]],
) -> Vec<(usize, [[f64; D]; D])> {
    let mut blocks: Vec<usize> = loads.iter().filter(|l| l.weight > 0.0).map(|l| l.block).collect();
    blocks.sort_unstable();
    blocks.dedup();
    let on = |i: usize| loads.iter().filter(move |l| l.block == i && l.weight > 0.0);
    blocks
        .into_iter()
        .map(|i| {
            // the masses of the block and of its loads, each at its point
            let points: Vec<(f64, [f64; D])> =
                std::iter::once((mass[i], centre[i])).chain(on(i).map(|l| (l.weight / gravity, l.point))).collect();
            let total: f64 = points.iter().map(|p| p.0).sum();
            let mut c = [0.0; D];
            for (m, p) in &points {
                for k in 0..D {
                    c[k] += m * p[k] / total;
                }
            }
            let mut s = [[0.0; D]; D];
            for (m, p) in &points {
                let r: [f64; D] = std::array::from_fn(|k| p[k] - c[k]);
                for a in 0..D {
                    for b in 0..D {
                        s[a][b] += m * r[a] * r[b];
                    }
                }
            }
            mass[i] = total;
            centre[i] = c;
            (i, s)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lumping_keeps_the_first_moment_and_adds_the_parallel_axis_terms() {
        // a 10 kg block at the origin and 30 kg (294.3 N at g = 9.81) at (2, 0): the centre at
        // (1.5, 0), the second moment 10 * 1.5^2 + 30 * 0.5^2 = 30 kg m2 along x
        let loads = [CarriedLoad { block: 0, point: [2.0, 0.0], weight: 294.3 }];
        let (mut mass, mut centre) = (vec![10.0], vec![[0.0, 0.0]]);
        let s = lump(&loads, 9.81, &mut mass, &mut centre);
        assert!((mass[0] - 40.0).abs() < 1e-12 && (centre[0][0] - 1.5).abs() < 1e-12 && centre[0][1] == 0.0);
        assert_eq!(s.len(), 1);
        assert!((s[0].1[0][0] - 30.0).abs() < 1e-12 && s[0].1[1][1] == 0.0 && s[0].1[0][1] == 0.0);
    }

    #[test]
    fn refusals_name_the_load() {
        let bad = |l: CarriedLoad<2>| check(&[CarriedLoad { block: 0, point: [0.0, 0.0], weight: 1.0 }, l], 2, 9.81).unwrap_err();
        let e = bad(CarriedLoad { block: 2, point: [0.0, 0.0], weight: 1.0 });
        assert_eq!(e.key(), Some("loads.carried[1]"));
        assert!(e.to_string().starts_with("loads.carried[1]: block 2 is not a wall block"), "{e}");
        let e = bad(CarriedLoad { block: 1, point: [0.0, 0.0], weight: -1.0 });
        assert!(e.to_string().contains("weight must be finite and not negative"), "{e}");
        let e = bad(CarriedLoad { block: 1, point: [0.0, 0.0], weight: f64::NAN });
        assert!(e.to_string().contains("weight must be finite"), "{e}");
        let e = bad(CarriedLoad { block: 1, point: [f64::INFINITY, 0.0], weight: 1.0 });
        assert!(e.to_string().contains("must be finite"), "{e}");
        let e = check(&[CarriedLoad { block: 0, point: [0.0, 0.0], weight: 1.0 }], 1, 0.0).unwrap_err();
        assert!(e.to_string().contains("needs gravity > 0"), "{e}");
    }
}
