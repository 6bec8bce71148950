//! The F3 march of several strips at once in SIMD lanes (x86-64): SSE2 (two strips per
//! register, every x86-64 processor) and AVX (four per register, chosen at run time where the
//! processor has it).
//!
//! Why: in a slip zone each strip's march is a chain of dependent operations — a square root and
//! a division per element ([`StripMarch::step`]) — so one strip at a time leaves the processor
//! waiting on that chain. Strips in lanes share one packed square root and division per
//! element, and several registers marched in one loop overlap their chains.
//!
//! Exactness: every lane operation is the IEEE operation of [`StripMarch::element`] and
//! [`StripMarch::step`] in the same order (separate multiplies and adds, no fused
//! multiply-add), so each strip's tractions, slip flags and sums are bit for bit those of the
//! scalar [`StripMarch::run`] (tested). An adhering lane next to a slipping one takes the scale
//! factor 1 (its traction is unchanged: t·1 = t) and adds an exact zero to its power sum.
//!
//! Safety: the intrinsics only compute on registers; memory is accessed through bounds-checked
//! slices. SSE2 belongs to the x86-64 baseline; the AVX march runs only after
//! `is_x86_feature_detected!("avx")` (see [`march`]).

use super::{StripMarch, StripOut, StripSums};
use std::arch::x86_64::*;

/// The packed operations the march needs, on a register of [`Packed::LANES`] doubles.
trait Packed: Copy {
    const LANES: usize;
    /// Lanes from `values` (one per lane).
    unsafe fn load(values: &[f64]) -> Self;
    unsafe fn splat(v: f64) -> Self;
    unsafe fn store(self, out: &mut [f64; 4]);
    unsafe fn add(self, o: Self) -> Self;
    unsafe fn sub(self, o: Self) -> Self;
    unsafe fn mul(self, o: Self) -> Self;
    unsafe fn div(self, o: Self) -> Self;
    unsafe fn sqrt(self) -> Self;
    unsafe fn max(self, o: Self) -> Self;
    /// All-ones lanes where self > o.
    unsafe fn greater(self, o: Self) -> Self;
    /// Bit k set where lane k of the mask is set.
    unsafe fn mask_bits(self) -> u32;
    /// `if_set` in the lanes set in `mask`, `otherwise` elsewhere.
    unsafe fn select(mask: Self, if_set: Self, otherwise: Self) -> Self;
}

impl Packed for __m128d {
    const LANES: usize = 2;
    #[inline(always)]
    unsafe fn load(values: &[f64]) -> Self {
        _mm_set_pd(values[1], values[0])
    }
    #[inline(always)]
    unsafe fn splat(v: f64) -> Self {
        _mm_set1_pd(v)
    }
    #[inline(always)]
    unsafe fn store(self, out: &mut [f64; 4]) {
        _mm_storeu_pd(out.as_mut_ptr(), self);
    }
    #[inline(always)]
    unsafe fn add(self, o: Self) -> Self {
        _mm_add_pd(self, o)
    }
    #[inline(always)]
    unsafe fn sub(self, o: Self) -> Self {
        _mm_sub_pd(self, o)
    }
    #[inline(always)]
    unsafe fn mul(self, o: Self) -> Self {
        _mm_mul_pd(self, o)
    }
    #[inline(always)]
    unsafe fn div(self, o: Self) -> Self {
        _mm_div_pd(self, o)
    }
    #[inline(always)]
    unsafe fn sqrt(self) -> Self {
        _mm_sqrt_pd(self)
    }
    #[inline(always)]
    unsafe fn max(self, o: Self) -> Self {
        _mm_max_pd(self, o)
    }
    #[inline(always)]
    unsafe fn greater(self, o: Self) -> Self {
        _mm_cmpgt_pd(self, o)
    }
    #[inline(always)]
    unsafe fn mask_bits(self) -> u32 {
        _mm_movemask_pd(self) as u32
    }
    #[inline(always)]
    unsafe fn select(mask: Self, if_set: Self, otherwise: Self) -> Self {
        _mm_or_pd(_mm_and_pd(mask, if_set), _mm_andnot_pd(mask, otherwise))
    }
}

impl Packed for __m256d {
    const LANES: usize = 4;
    #[inline(always)]
    unsafe fn load(values: &[f64]) -> Self {
        _mm256_set_pd(values[3], values[2], values[1], values[0])
    }
    #[inline(always)]
    unsafe fn splat(v: f64) -> Self {
        _mm256_set1_pd(v)
    }
    #[inline(always)]
    unsafe fn store(self, out: &mut [f64; 4]) {
        _mm256_storeu_pd(out.as_mut_ptr(), self);
    }
    #[inline(always)]
    unsafe fn add(self, o: Self) -> Self {
        _mm256_add_pd(self, o)
    }
    #[inline(always)]
    unsafe fn sub(self, o: Self) -> Self {
        _mm256_sub_pd(self, o)
    }
    #[inline(always)]
    unsafe fn mul(self, o: Self) -> Self {
        _mm256_mul_pd(self, o)
    }
    #[inline(always)]
    unsafe fn div(self, o: Self) -> Self {
        _mm256_div_pd(self, o)
    }
    #[inline(always)]
    unsafe fn sqrt(self) -> Self {
        _mm256_sqrt_pd(self)
    }
    #[inline(always)]
    unsafe fn max(self, o: Self) -> Self {
        _mm256_max_pd(self, o)
    }
    #[inline(always)]
    unsafe fn greater(self, o: Self) -> Self {
        _mm256_cmp_pd::<_CMP_GT_OQ>(self, o)
    }
    #[inline(always)]
    unsafe fn mask_bits(self) -> u32 {
        _mm256_movemask_pd(self) as u32
    }
    #[inline(always)]
    unsafe fn select(mask: Self, if_set: Self, otherwise: Self) -> Self {
        _mm256_blendv_pd(otherwise, if_set, mask)
    }
}

/// One register's strips: march constants and running state, lane k for strip k.
#[derive(Clone, Copy)]
struct Lanes<V> {
    x_first: V,
    dx: V,
    step_y_at_zero: V,
    step_y_per_x: V,
    spin_offset: V,
    bound_scale: V,
    step_x: V,
    lx: V,
    ly: V,
    fraction: V,
    px: V,
    py: V,
    sum_px: V,
    sum_py: V,
    sum_x_py: V,
    sum_power: V,
    max_power: V,
    max_slip: V,
    max_sq: V,
    /// Adhering elements per lane, counted in f64 (exact below 2⁵³).
    n_adhesion: V,
}

impl<V: Packed> Lanes<V> {
    /// Lanes for `marches` (one per lane) with x steps `step_x`.
    #[inline(always)]
    unsafe fn new(marches: &[&StripMarch], step_x: &[f64]) -> Self {
        let of = |field: fn(&StripMarch) -> f64| {
            let mut v = [0.0; 4];
            for (slot, m) in v.iter_mut().zip(marches) {
                *slot = field(m);
            }
            V::load(&v)
        };
        let zero = V::splat(0.0);
        Self {
            x_first: of(|m| m.x_first),
            dx: of(|m| m.dx),
            step_y_at_zero: of(|m| m.step_y_at_zero),
            step_y_per_x: of(|m| m.step_y_per_x),
            spin_offset: of(|m| m.spin_offset),
            bound_scale: of(|m| m.bound_scale),
            step_x: V::load(step_x),
            lx: of(|m| m.slip_flexibility[0]),
            ly: of(|m| m.slip_flexibility[1]),
            fraction: of(|m| m.lead_fraction),
            px: zero,
            py: zero,
            sum_px: zero,
            sum_py: zero,
            sum_x_py: zero,
            sum_power: zero,
            max_power: zero,
            max_slip: zero,
            max_sq: zero,
            n_adhesion: zero,
        }
    }

    /// Element `i` (`index` = i as f64 in every lane, bound shape `shape_factor`) of every
    /// lane's strip, written to `out` (one per lane).
    #[inline(always)]
    unsafe fn step(&mut self, i: usize, index: V, shape_factor: V, out: &mut [StripOut<'_>]) {
        let one = V::splat(1.0);
        let f = self.fraction;
        self.fraction = one;
        // `StripMarch::element`.
        let x = self.x_first.add(index.mul(self.dx));
        let spin_x = x.add(f.mul(self.spin_offset));
        let step_y = f.mul(self.step_y_at_zero.add(self.step_y_per_x.mul(spin_x)));
        let bound = self.bound_scale.mul(shape_factor);
        // `StripMarch::step`.
        let trial_x = self.px.sub(f.mul(self.step_x));
        let trial_y = self.py.sub(step_y);
        let trial_sq = trial_x.mul(trial_x).add(trial_y.mul(trial_y));
        let slip = trial_sq.greater(bound.mul(bound));
        let slip_bits = slip.mask_bits();
        // Each lane's slip displacement |S| (0 where it adheres: its scale is 1).
        let mut slip_len = V::splat(0.0);
        if slip_bits == 0 {
            self.px = trial_x;
            self.py = trial_y;
        } else {
            let scale = V::select(slip, bound.div(trial_sq.sqrt()), one);
            self.px = trial_x.mul(scale);
            self.py = trial_y.mul(scale);
            let sx = self.lx.mul(self.px.sub(trial_x));
            let sy = self.ly.mul(self.py.sub(trial_y));
            let slip_sq = sx.mul(sx).add(sy.mul(sy));
            slip_len = slip_sq.sqrt();
            let power = bound.mul(slip_len);
            self.sum_power = self.sum_power.add(power);
            self.max_power = power.max(self.max_power);
            self.max_slip = slip_len.max(self.max_slip);
        }
        let (mut px, mut py) = ([0.0; 4], [0.0; 4]);
        self.px.store(&mut px);
        self.py.store(&mut py);
        for (lane, o) in out.iter_mut().enumerate().take(V::LANES) {
            o.px[i] = px[lane];
            o.py[i] = py[lane];
            o.slipping[i] = slip_bits & (1 << lane) != 0;
        }
        // The slips where recorded (all lanes' or none: `strip_outs`).
        if !out[0].slip.is_empty() {
            let mut lens = [0.0; 4];
            slip_len.store(&mut lens);
            for (lane, o) in out.iter_mut().enumerate().take(V::LANES) {
                o.slip[i] = lens[lane];
            }
        }
        self.n_adhesion = self.n_adhesion.add(V::select(slip, V::splat(0.0), one));
        self.sum_px = self.sum_px.add(self.px);
        self.sum_py = self.sum_py.add(self.py);
        self.sum_x_py = self.sum_x_py.add(x.mul(self.py));
        let traction_sq = self.px.mul(self.px).add(self.py.mul(self.py));
        // Operands in this order: a NaN traction (none arises from finite inputs) leaves the
        // maximum as f64::max does in the scalar march (maxpd returns its second operand then).
        self.max_sq = traction_sq.max(self.max_sq);
    }

    /// The lanes' sums into `sums` (one per lane).
    #[inline(always)]
    unsafe fn finish(&self, sums: &mut [StripSums]) {
        let mut columns = [[0.0; 4]; 8];
        for (v, c) in [
            self.sum_px,
            self.sum_py,
            self.sum_x_py,
            self.sum_power,
            self.max_sq,
            self.n_adhesion,
            self.max_power,
            self.max_slip,
        ]
        .iter()
        .zip(columns.iter_mut())
        {
            v.store(c);
        }
        for (lane, s) in sums.iter_mut().enumerate().take(V::LANES) {
            s.sum_px = columns[0][lane];
            s.sum_py = columns[1][lane];
            s.sum_x_py = columns[2][lane];
            s.sum_power = columns[3][lane];
            s.max_traction_sq = columns[4][lane];
            s.n_adhesion = columns[5][lane] as usize;
            s.max_power = columns[6][lane];
            s.max_slip = columns[7][lane];
        }
    }
}

/// Most strips marched together: two registers of four lanes.
pub(crate) const MAX_GROUP: usize = 8;

/// `R` registers of `V` (R × LANES strips: `marches`, `step_x`, `out`, `sums`, one per strip)
/// over the elements of `shape`, all registers in one loop.
#[inline(always)]
unsafe fn march_in<V: Packed, const R: usize>(
    marches: &[&StripMarch],
    step_x: &[f64],
    shape: &[f64],
    out: &mut [StripOut<'_>],
    sums: &mut [StripSums],
) {
    let lanes = V::LANES;
    let mut registers: [Lanes<V>; R] = std::array::from_fn(|r| {
        let strips = r * lanes..(r + 1) * lanes;
        Lanes::new(&marches[strips.clone()], &step_x[strips])
    });
    for (i, &shape_factor) in shape.iter().enumerate().rev() {
        let index = V::splat(i as f64);
        let shape_factor = V::splat(shape_factor);
        for (register, o) in registers.iter_mut().zip(out.chunks_exact_mut(lanes)) {
            register.step(i, index, shape_factor, o);
        }
    }
    for (register, s) in registers.iter().zip(sums.chunks_exact_mut(lanes)) {
        register.finish(s);
    }
}

/// [`march_in`] with AVX enabled (its inlined operations compile to 256-bit instructions).
#[target_feature(enable = "avx")]
unsafe fn march_avx<const R: usize>(
    marches: &[&StripMarch],
    step_x: &[f64],
    shape: &[f64],
    out: &mut [StripOut<'_>],
    sums: &mut [StripSums],
) {
    march_in::<__m256d, R>(marches, step_x, shape, out, sums);
}

/// Marches `marches.len()` strips (2, 4 or [`MAX_GROUP`]; `step_x`, `out` and the returned
/// sums one per strip) over the elements of `shape`: with AVX (detected at run time) in
/// registers of four strips, otherwise in SSE2 registers of two. Results are those of
/// [`StripMarch::run`] on each strip, bit for bit.
pub(crate) fn march(
    marches: &[&StripMarch],
    step_x: &[f64],
    shape: &[f64],
    out: &mut [StripOut<'_>],
) -> [StripSums; MAX_GROUP] {
    let n = marches.len();
    assert!(matches!(n, 2 | 4 | MAX_GROUP) && step_x.len() == n && out.len() == n);
    let mut sums = [StripSums::default(); MAX_GROUP];
    for (s, o) in sums.iter_mut().zip(out.iter()) {
        *s = StripMarch::start_sums(shape, o);
    }
    let avx = n >= 4 && std::is_x86_feature_detected!("avx");
    let sums_out = &mut sums[..n];
    // SAFETY: see the module header — AVX only where detected, SSE2 always present.
    unsafe {
        match (n, avx) {
            (MAX_GROUP, true) => march_avx::<2>(marches, step_x, shape, out, sums_out),
            (4, true) => march_avx::<1>(marches, step_x, shape, out, sums_out),
            (MAX_GROUP, false) => march_in::<__m128d, 4>(marches, step_x, shape, out, sums_out),
            (4, false) => march_in::<__m128d, 2>(marches, step_x, shape, out, sums_out),
            _ => march_in::<__m128d, 1>(marches, step_x, shape, out, sums_out),
        }
    }
    sums
}
