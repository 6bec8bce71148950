//! Small dense linear systems on fixed buffers (no allocation).

/// Solves the `size`² system in `a` (row stride `stride`, overwritten) for `b` in place by
/// Gaussian elimination with partial pivoting; `false` for a singular (or non-finite) matrix.
pub fn lu_solve(a: &mut [f64], stride: usize, size: usize, b: &mut [f64]) -> bool {
    for col in 0..size {
        let mut pivot = col;
        for r in col + 1..size {
            if a[r * stride + col].abs() > a[pivot * stride + col].abs() {
                pivot = r;
            }
        }
        let p = a[pivot * stride + col];
        if !(p.abs() > 0.0 && p.is_finite()) {
            return false;
        }
        if pivot != col {
            for c in col..size {
                a.swap(pivot * stride + c, col * stride + c);
            }
            b.swap(pivot, col);
        }
        // Rows below the pivot row, as slices (no index arithmetic in the inner loop).
        let (upper, lower) = a.split_at_mut((col + 1) * stride);
        let pivot_row = &upper[col * stride + col + 1..col * stride + size];
        let b_col = b[col];
        for (k, row) in lower.chunks_mut(stride).take(size - col - 1).enumerate() {
            let factor = row[col] / p;
            if factor != 0.0 {
                for (x, u) in row[col + 1..size].iter_mut().zip(pivot_row) {
                    *x -= factor * u;
                }
                b[col + 1 + k] -= factor * b_col;
            }
        }
    }
    for col in (0..size).rev() {
        let row = &a[col * stride..col * stride + size];
        let sum: f64 = row[col + 1..]
            .iter()
            .zip(&b[col + 1..size])
            .map(|(u, x)| u * x)
            .sum();
        b[col] = (b[col] - sum) / row[col];
    }
    b.iter().all(|v| v.is_finite())
}
