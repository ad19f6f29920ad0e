//! The few operations on 3-vectors that the 3D shapes need.

pub(crate) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

pub(crate) fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// `a` over its length (an axis-aligned vector stays exact: `sqrt(x^2)` is `|x|`).
pub(crate) fn unit(a: [f64; 3]) -> [f64; 3] {
    let l = norm(a);
    a.map(|v| v / l)
}


/// The rotation by the angle `|w|` \[rad\] about the axis `w`, as a matrix (Rodrigues' formula;
/// the identity for `w` = 0).
pub(crate) fn rotation(w: [f64; 3]) -> [[f64; 3]; 3] {
    let theta = norm(w);
    if theta == 0.0 {
        return [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    }
    let k = w.map(|v| v / theta);
    let (s, c) = theta.sin_cos();
    // 1 - cos(theta) without the cancellation at small angles
    let v = 2.0 * (0.5 * theta).sin().powi(2);
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let skew = match (i, j) {
                (0, 1) => -k[2],
                (0, 2) => k[1],
                (1, 0) => k[2],
                (1, 2) => -k[0],
                (2, 0) => -k[1],
                (2, 1) => k[0],
                _ => 0.0,
            };
            (if i == j { c } else { 0.0 }) + s * skew + v * k[i] * k[j]
        })
    })
}

/// The product of the matrix `m` and the vector `x`.
pub(crate) fn apply(m: &[[f64; 3]; 3], x: [f64; 3]) -> [f64; 3] {
    m.map(|row| dot(row, x))
}
