//! The discrete convolution u = C * p by FFT (DC-FFT, Liu, Wang & Liu 2000).
//!
//! The (2nx − 1) × (2ny − 1) block of influence coefficients is wrapped onto a zero-padded
//! periodic mx × my grid, mx ≥ 2nx − 1 and my ≥ 2ny − 1, so the periodic convolution of the
//! zero-padded pressure equals the linear one on the nx × ny grid exactly (no periodicity
//! error). The 2-D transform is real-to-complex along x (`realfft`), keeping the Hermitian half
//! kx = 0 … mx/2, then complex along y (`rustfft`); the half-spectrum is stored column by column
//! (index `kx * my + ky`) so that every y transform runs on a contiguous slice.

use std::sync::Arc;

use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::{Fft, FftPlanner};

use crate::grid::Grid;
use crate::influence::influence_coefficient;

/// u = C * p on one grid, with the FFT plans, the kernel's spectrum and the work buffers made
/// once: every [`Convolution::apply`] afterwards only transforms.
pub(crate) struct Convolution {
    nx: usize,
    ny: usize,
    /// Padded length along y (the column transforms' length).
    my: usize,
    rows_forward: Arc<dyn RealToComplex<f64>>,
    rows_inverse: Arc<dyn ComplexToReal<f64>>,
    columns_forward: Arc<dyn Fft<f64>>,
    columns_inverse: Arc<dyn Fft<f64>>,
    /// Spectrum of the wrapped coefficient block (real: the block is even in x and in y), times
    /// the 1/(mx my) of the unnormalised inverse transform; column by column.
    kernel: Vec<f64>,
    /// Half-spectrum, column by column: (mx/2 + 1) columns of my.
    spectrum: Vec<Complex<f64>>,
    /// One padded real row (mx).
    row: Vec<f64>,
    /// One row's half-spectrum (mx/2 + 1).
    row_spectrum: Vec<Complex<f64>>,
    scratch: Vec<Complex<f64>>,
}

impl Convolution {
    /// Plans the transforms for `grid` and transforms its influence coefficients for the
    /// contact modulus `e_star` [Pa]. The grid must be valid ([`Grid::validate`]).
    pub(crate) fn new(grid: &Grid, e_star: f64) -> Self {
        let mx = padded_length(grid.nx);
        let my = padded_length(grid.ny);
        let mut real_planner = RealFftPlanner::<f64>::new();
        let rows_forward = real_planner.plan_fft_forward(mx);
        let rows_inverse = real_planner.plan_fft_inverse(mx);
        let mut planner = FftPlanner::<f64>::new();
        let columns_forward = planner.plan_fft_forward(my);
        let columns_inverse = planner.plan_fft_inverse(my);
        let scratch_len = [
            rows_forward.get_scratch_len(),
            rows_inverse.get_scratch_len(),
            columns_forward.get_inplace_scratch_len(),
            columns_inverse.get_inplace_scratch_len(),
        ]
        .into_iter()
        .max()
        .unwrap_or(0);
        let half = rows_forward.complex_len();
        let mut conv = Self {
            nx: grid.nx,
            ny: grid.ny,
            my,
            row: rows_forward.make_input_vec(),
            row_spectrum: rows_forward.make_output_vec(),
            rows_forward,
            rows_inverse,
            columns_forward,
            columns_inverse,
            kernel: Vec::new(),
            spectrum: vec![Complex::default(); half * my],
            scratch: vec![Complex::default(); scratch_len],
        };
        let block = wrapped_coefficients(grid, e_star, mx, my);
        conv.forward(&block, mx, my);
        let norm = 1.0 / (mx * my) as f64;
        conv.kernel = conv.spectrum.iter().map(|z| z.re * norm).collect();
        conv
    }

    /// out = C * input, both nx × ny row-major.
    pub(crate) fn apply(&mut self, input: &[f64], out: &mut [f64]) {
        debug_assert_eq!(input.len(), self.nx * self.ny);
        debug_assert_eq!(out.len(), self.nx * self.ny);
        self.forward(input, self.nx, self.ny);
        for (z, &c) in self.spectrum.iter_mut().zip(&self.kernel) {
            *z *= c;
        }
        self.columns_inverse
            .process_with_scratch(&mut self.spectrum, &mut self.scratch);
        let (nx, my) = (self.nx, self.my);
        for (j, out_row) in out.chunks_exact_mut(nx).enumerate() {
            gather_row(&self.spectrum, my, j, &mut self.row_spectrum);
            drop_edge_imaginary_parts(&mut self.row_spectrum, self.row.len());
            self.rows_inverse
                .process_with_scratch(&mut self.row_spectrum, &mut self.row, &mut self.scratch)
                .expect("buffer lengths from the plan");
            out_row.copy_from_slice(&self.row[..nx]);
        }
    }

    /// Half-spectrum of the real `w` × `h` field `input` (row-major), zero-padded to mx × my,
    /// into `self.spectrum`.
    fn forward(&mut self, input: &[f64], w: usize, h: usize) {
        let my = self.my;
        for (j, input_row) in input.chunks_exact(w).take(h).enumerate() {
            self.row[..w].copy_from_slice(input_row);
            self.row[w..].fill(0.0);
            self.rows_forward
                .process_with_scratch(&mut self.row, &mut self.row_spectrum, &mut self.scratch)
                .expect("buffer lengths from the plan");
            scatter_row(&self.row_spectrum, my, j, &mut self.spectrum);
        }
        for column in self.spectrum.chunks_exact_mut(my) {
            column[h..].fill(Complex::default());
        }
        self.columns_forward
            .process_with_scratch(&mut self.spectrum, &mut self.scratch);
    }
}

/// Padded length for n elements: the smallest even m ≥ 2n − 1 whose only prime factors are 2,
/// 3 and 5 (fast transforms, little padding).
fn padded_length(n: usize) -> usize {
    let mut m = (2 * n).saturating_sub(1).max(2);
    m += m % 2;
    while !is_5_smooth(m) {
        m += 2;
    }
    m
}

/// True when m ≥ 1 has no prime factor other than 2, 3 and 5.
fn is_5_smooth(mut m: usize) -> bool {
    for f in [2, 3, 5] {
        while m % f == 0 {
            m /= f;
        }
    }
    m == 1
}

/// The influence coefficient of every offset (m dx, l dy), −n < m, l < n, at (m mod mx,
/// l mod my) of a zero mx × my row-major block.
fn wrapped_coefficients(grid: &Grid, e_star: f64, mx: usize, my: usize) -> Vec<f64> {
    let mut block = vec![0.0; mx * my];
    for l in 0..grid.ny {
        let y = l as f64 * grid.dy;
        for m in 0..grid.nx {
            let x = m as f64 * grid.dx;
            let c = influence_coefficient(grid.dx, grid.dy, x, y, e_star);
            // The coefficient is even in x and in y: the four images at once.
            for ll in [l, (my - l) % my] {
                for mm in [m, (mx - m) % mx] {
                    block[ll * mx + mm] = c;
                }
            }
        }
    }
    block
}

/// Row j of the half-spectrum (one value per column of length `my`) into the column-by-column
/// `spectrum`.
fn scatter_row(row: &[Complex<f64>], my: usize, j: usize, spectrum: &mut [Complex<f64>]) {
    for (column, &z) in spectrum.chunks_exact_mut(my).zip(row) {
        column[j] = z;
    }
}

/// Row j of the column-by-column `spectrum` (columns of length `my`).
fn gather_row(spectrum: &[Complex<f64>], my: usize, j: usize, row: &mut [Complex<f64>]) {
    for (z, column) in row.iter_mut().zip(spectrum.chunks_exact(my)) {
        *z = column[j];
    }
}

/// The half-spectrum of a real row of length `len` has real values at kx = 0 and, for even
/// `len`, at kx = len/2; after the y transforms they carry round-off imaginary parts, which the
/// complex-to-real transform rejects. Sets them to their exact value, zero.
fn drop_edge_imaginary_parts(row: &mut [Complex<f64>], len: usize) {
    row[0].im = 0.0;
    if len % 2 == 0 {
        row[len / 2].im = 0.0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::e_star;

    #[test]
    fn padded_lengths_are_even_smooth_and_long_enough() {
        assert_eq!(padded_length(1), 2);
        assert_eq!(padded_length(45), 90);
        assert_eq!(padded_length(200), 400);
        assert_eq!(padded_length(256), 512);
        for n in 1..300 {
            let m = padded_length(n);
            assert!(m >= 2 * n - 1 && m % 2 == 0 && is_5_smooth(m), "{n}: {m}");
        }
        assert!(!is_5_smooth(14) && is_5_smooth(1));
    }

    /// Deterministic pseudo-random pressures up to 1 GPa.
    fn pressures(n: usize) -> Vec<f64> {
        let mut seed = 12345u64;
        (0..n)
            .map(|_| {
                seed = seed
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (seed >> 11) as f64 / (1u64 << 53) as f64 * 1e9
            })
            .collect()
    }

    /// u = C * p summed element by element.
    fn direct_sum(grid: &Grid, p: &[f64], es: f64) -> Vec<f64> {
        let (nx, ny) = (grid.nx, grid.ny);
        let mut u = vec![0.0; grid.len()];
        for j in 0..ny {
            for i in 0..nx {
                for jj in 0..ny {
                    for ii in 0..nx {
                        let x = (i as f64 - ii as f64) * grid.dx;
                        let y = (j as f64 - jj as f64) * grid.dy;
                        let c = influence_coefficient(grid.dx, grid.dy, x, y, es);
                        u[j * nx + i] += c * p[jj * nx + ii];
                    }
                }
            }
        }
        u
    }

    #[test]
    fn fft_convolution_equals_direct_sum() {
        let es = e_star();
        for &(nx, ny) in &[(1, 1), (1, 4), (7, 5), (12, 9), (16, 3)] {
            let grid = Grid::centred(nx, ny, 0.7e-3, 1.3e-3);
            let p = pressures(grid.len());
            let mut conv = Convolution::new(&grid, es);
            let mut u = vec![0.0; grid.len()];
            // Twice: the plans and buffers are reused.
            for _ in 0..2 {
                conv.apply(&p, &mut u);
                let direct = direct_sum(&grid, &p, es);
                let max_u = direct.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                let max_err = u
                    .iter()
                    .zip(&direct)
                    .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
                assert!(max_err < 1e-13 * max_u, "{nx}x{ny}: {max_err} vs {max_u}");
            }
        }
    }
}
