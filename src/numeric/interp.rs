//! Polynomial interpolation weights.

/// Weights of 4-point (cubic) Lagrange interpolation on the nodes −1, 0, 1, 2 at offset `x`
/// (x ∈ [0, 1] between nodes 0 and 1).
pub fn cubic_lagrange_weights(x: f64) -> [f64; 4] {
    [
        -x * (x - 1.0) * (x - 2.0) / 6.0,
        (x + 1.0) * (x - 1.0) * (x - 2.0) / 2.0,
        -(x + 1.0) * x * (x - 2.0) / 2.0,
        (x + 1.0) * x * (x - 1.0) / 6.0,
    ]
}

/// Cubic (Lagrange) interpolation of the uniformly spaced `values` (at least 4) at the
/// fractional node index `x` ≥ 0: the interval [k, k + 1] containing x, with its neighbours
/// k − 1 and k + 2 kept inside the table (extrapolated at the ends).
pub fn cubic_on_uniform_nodes(values: &[f64], x: f64) -> f64 {
    // `as usize` floors a non-negative value (and saturates below 0) without a call to libm's
    // floor, which baseline x86-64 (no SSE4.1 rounding) would need.
    let k = (x as usize).clamp(1, values.len() - 3);
    let w = cubic_lagrange_weights(x - k as f64);
    w[0] * values[k - 1] + w[1] * values[k] + w[2] * values[k + 1] + w[3] * values[k + 2]
}
