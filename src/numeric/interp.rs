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
