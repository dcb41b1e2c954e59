//! One row of the resolvent of a real state matrix at one frequency, c (iωI − A)⁻¹: the transposed system
//! (iωI − Aᵀ) x = cᵀ solved in one buffer (on the stack up to order 16, stored by columns as nalgebra stores
//! it) by LU with partial pivoting in the steps of nalgebra's `LU::new` and `LU::solve` (the same pivot
//! choice by |re| + |im|, the same multiplier by the pivot's reciprocal, the same updates in the same order,
//! the same divisions by L's unit diagonal), so that the values are those of `DMatrix::lu().solve()` on the
//! same matrix (`tests::the_values_of_nalgebras_lu`): route 1's variances, and through them route 2's
//! histograms, keep the numbers of a seed. One difference in form: nalgebra's `axpy` computes
//! y ← (a·x)·1 + 1·y, and the two unit factors are left out (y ← a·x + y). They are exact for every finite
//! non-zero part, so what can differ is the sign of a zero part (0 against −0; it reaches x where cᵀ or A
//! has signed zeros) and, past overflow (entries near 10³⁰⁸, or a pivot below 10⁻¹⁵⁴ whose |·|² underflows),
//! which non-finite value a part holds (nalgebra's ·1 turns an infinity beside a finite part into NaN, and
//! spreads a NaN to both parts). No variance reads either: |H|², and sums of products with finite weights,
//! are the same for 0 and −0, and a non-finite node fails the quadrature either way. A quadrature
//! evaluates this row at every node; the heap matrices, the permutation, the solve's copy of the
//! right-hand side and the unit factors were most of its cost for the small orders of a machine model. It
//! stays an O(n³) solve per node: a reduction of A once per system (Hessenberg or modal form) would make it
//! O(n²) or O(n), with other roundings, i.e. other numbers of a seed for route 2.
//!
//! # Formula
//! For k = 0 … n−1: the pivot row p ≥ k maximises |Re m_pk| + |Im m_pk| (the first such row); rows k and p
//! swap; the column below the pivot is multiplied by 1/m_kk; each later column j gets
//! m_ij ← (−m_kj)·m_ik + m_ij (i > k). A zero pivot skips the column (as nalgebra). The solve permutes cᵀ,
//! runs forward substitution with the unit diagonal (dividing by 1 + 0i) and back substitution; a zero
//! diagonal of U is a singular system (`false`).

use nalgebra::{Complex, DMatrix};

type C64 = Complex<f64>;

/// The largest order solved here ([`solve_shifted_transpose`]): orders up to 16 on the stack (one copy of
/// the loops per order), larger ones in one heap buffer; above, nalgebra's LU.
pub const SHIFTED_MAX: usize = 64;

/// Solves (iωI − Aᵀ) x = cᵀ for a square `a` of order n ≤ [`SHIFTED_MAX`] (n ≥ 1) into `x[..n]`. Returns
/// false where nalgebra's solve returns `None` (a zero on U's diagonal); `x` then holds no meaning.
///
/// # Panics
/// If n is 0 or above [`SHIFTED_MAX`], or `c` or `x` is shorter than n (a caller's bug: the callers check).
pub fn solve_shifted_transpose(a: &DMatrix<f64>, c: &[f64], omega: f64, x: &mut [C64]) -> bool {
    let n = a.nrows();
    assert!((1..=SHIFTED_MAX).contains(&n) && a.ncols() == n && c.len() >= n && x.len() >= n);
    // the small orders with arrays of exactly n × n and loops of known length, one copy per order
    macro_rules! by_order {
        ($($n:literal)*) => {
            match n {
                $($n => {
                    let mut m = [[C64::new(0.0, 0.0); $n]; $n];
                    let mut swaps = [(0usize, 0usize); $n];
                    solve_in(m.as_flattened_mut(), &mut swaps, a, c, omega, &mut x[..$n])
                })*
                _ => {
                    let mut m = vec![C64::new(0.0, 0.0); n * n];
                    let mut swaps = vec![(0usize, 0usize); n];
                    solve_in(&mut m, &mut swaps, a, c, omega, &mut x[..n])
                }
            }
        };
    }
    by_order!(1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16)
}

/// The solve in `m` (n × n by columns, as nalgebra stores it: entry (r, k) at k·n + r; n = `b.len()`)
/// with room for n row swaps.
#[inline(always)]
fn solve_in(
    m: &mut [C64],
    swaps: &mut [(usize, usize)],
    a: &DMatrix<f64>,
    c: &[f64],
    omega: f64,
    b: &mut [C64],
) -> bool {
    let n = b.len();
    let s = C64::new(0.0, omega);
    // column k of iωI − Aᵀ is row k of A, negated, with iω on the diagonal
    for (k, col) in m.chunks_exact_mut(n).enumerate() {
        for (r, v) in col.iter_mut().enumerate() {
            let e = C64::new(-a[(k, r)], 0.0);
            *v = if r == k { e + s } else { e };
        }
    }
    let n_swaps = factor(m, n, swaps);
    for (v, &cr) in b.iter_mut().zip(c) {
        *v = C64::new(cr, 0.0);
    }
    for &(i, j) in &swaps[..n_swaps] {
        b.swap(i, j);
    }
    solve_factored(m, b)
}

/// nalgebra's `axpy` update (`y = a·x·c + β·y` with c = β = 1) without its unit factors (module docs).
#[inline(always)]
fn axpy_one(a: C64, x: C64, y: C64) -> C64 {
    a * x + y
}

/// The pivot's size as nalgebra's `icamax` compares it (simba's `norm1`).
#[inline(always)]
fn norm1(v: C64) -> f64 {
    v.re.abs() + v.im.abs()
}

/// `LU::new` in place on `m` (n × n by columns); returns the number of row swaps recorded in `swaps`.
#[inline(always)]
fn factor(m: &mut [C64], n: usize, swaps: &mut [(usize, usize)]) -> usize {
    let one = C64::new(1.0, 0.0);
    let mut n_swaps = 0;
    for i in 0..n {
        let col_i = &m[i * n..(i + 1) * n];
        let mut piv = i;
        let mut the_max = norm1(col_i[i]);
        for (r, &v) in col_i.iter().enumerate().skip(i + 1) {
            let val = norm1(v);
            if val > the_max {
                the_max = val;
                piv = r;
            }
        }
        let diag = col_i[piv];
        if diag.re == 0.0 && diag.im == 0.0 {
            continue;
        }
        if piv != i {
            // nalgebra swaps the rows of L already computed, then the pivot column's two entries, then each
            // later column's just before its update (which reads only that column and the multipliers):
            // the whole rows at once give the same values
            swaps[n_swaps] = (i, piv);
            n_swaps += 1;
            for col in m.chunks_exact_mut(n) {
                col.swap(i, piv);
            }
        }
        let inv_diag = one / diag;
        let (done, rest) = m.split_at_mut((i + 1) * n);
        let multipliers = &mut done[i * n + i + 1..];
        for v in multipliers.iter_mut() {
            *v *= inv_diag;
        }
        for col in rest.chunks_exact_mut(n) {
            let a = -col[i];
            for (y, &x) in col[i + 1..].iter_mut().zip(multipliers.iter()) {
                *y = axpy_one(a, x, *y);
            }
        }
    }
    n_swaps
}

/// `LU::solve` after the permutation: forward substitution with L's unit diagonal, then back
/// substitution; false at a zero of U's diagonal.
#[inline(always)]
fn solve_factored(m: &[C64], b: &mut [C64]) -> bool {
    let n = b.len();
    let one = C64::new(1.0, 0.0);
    for i in 0..n - 1 {
        let coeff = b[i] / one;
        let a = -coeff;
        let (_, below) = b.split_at_mut(i + 1);
        for (y, &x) in below.iter_mut().zip(&m[i * n + i + 1..(i + 1) * n]) {
            *y = axpy_one(a, x, *y);
        }
    }
    for i in (0..n).rev() {
        let diag = m[i * n + i];
        if diag.re == 0.0 && diag.im == 0.0 {
            return false;
        }
        let coeff = b[i] / diag;
        b[i] = coeff;
        let a = -coeff;
        for (y, &x) in b[..i].iter_mut().zip(&m[i * n..i * n + i]) {
            *y = axpy_one(a, x, *y);
        }
    }
    true
}

/// The same solve by nalgebra on the heap: (iωI − Aᵀ) as a `DMatrix`, `LU::new`, `LU::solve`; `None` where
/// the system is singular. The route for orders above [`SHIFTED_MAX`], and the oracle the stack route is
/// tested against.
pub fn solve_shifted_transpose_heap(a: &DMatrix<f64>, c: &[f64], omega: f64) -> Option<DMatrix<C64>> {
    let n = a.nrows();
    let s = C64::new(0.0, omega);
    let m = DMatrix::from_fn(n, n, |r, k| {
        let v = C64::new(-a[(k, r)], 0.0);
        if r == k {
            v + s
        } else {
            v
        }
    });
    let rhs = DMatrix::from_fn(n, 1, |r, _| C64::new(c[r], 0.0));
    m.lu().solve(&rhs)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn nalgebra_row(a: &DMatrix<f64>, c: &[f64], omega: f64) -> Option<Vec<C64>> {
        solve_shifted_transpose_heap(a, c, omega).map(|x| x.iter().copied().collect())
    }

    /// The bits of each part, a zero of either sign as +0 (module docs: only a zero's sign can differ).
    fn bits(v: &[C64]) -> Vec<(u64, u64)> {
        let b = |x: f64| if x == 0.0 { 0 } else { x.to_bits() };
        v.iter().map(|z| (b(z.re), b(z.im))).collect()
    }

    /// Every order 1 … SHIFTED_MAX (60 matrices each up to 16, 4 above), random matrices of mixed scales
    /// (entries spanning 10⁻⁶ … 10⁶, with zeros of both signs and repeated values, so that pivots tie and
    /// rows swap; cᵀ with zeros of both signs), frequencies from 0 up (at ω = 0 every imaginary part is
    /// zero), and singular cases (a zero matrix at ω = 0, a zero row): the same bits as nalgebra's LU but
    /// for the sign of a zero part, or both singular.
    #[test]
    fn the_values_of_nalgebras_lu() {
        use rand::{RngExt, SeedableRng};
        let mut rng = rand::rngs::Xoshiro256PlusPlus::seed_from_u64(0x9E37_79B9_7F4A_7C15);
        let mut u = move || rng.random::<f64>() - 0.5;
        let mut cases = 0;
        for n in 1..=SHIFTED_MAX {
            let trials = if n <= 16 { 60 } else { 4 };
            for trial in 0..trials {
                let mut a = DMatrix::from_fn(n, n, |_, _| {
                    let v = u();
                    match trial % 4 {
                        0 => v,
                        1 => v * 10f64.powf(12.0 * u()),
                        2 if v.abs() < 0.2 => 0.0f64.copysign(v),
                        3 if v.abs() < 0.25 => 1.0,
                        _ => -2.0 * v,
                    }
                });
                if trial == trials - 1 {
                    a.row_mut(n - 1).fill(0.0);
                }
                let c: Vec<f64> = (0..n)
                    .map(|_| {
                        let v = u();
                        if trial % 3 == 0 && v.abs() < 0.15 {
                            0.0f64.copysign(v)
                        } else {
                            v
                        }
                    })
                    .collect();
                for omega in [0.0, 1e-3 * u().abs(), u().abs(), 50.0 * u(), 1e4] {
                    let want = nalgebra_row(&a, &c, omega);
                    let mut x = vec![C64::new(f64::NAN, f64::NAN); n];
                    let ok = solve_shifted_transpose(&a, &c, omega, &mut x);
                    match want {
                        Some(w) => {
                            assert!(ok, "n = {n}, trial {trial}, ω = {omega}: singular here only");
                            assert_eq!(bits(&x), bits(&w), "n = {n}, trial {trial}, ω = {omega}");
                        }
                        None => assert!(!ok, "n = {n}, trial {trial}, ω = {omega}: nalgebra found it singular"),
                    }
                    cases += 1;
                }
            }
        }
        // a non-singular system whose solution has a zero part of the other sign than nalgebra's (found
        // by review): equal values, a zero's sign apart
        let a = DMatrix::from_row_slice(3, 3, &[0.783, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.974, 0.0]);
        let c = [0.0, -0.0, -0.498];
        let want = nalgebra_row(&a, &c, -3.0).expect("non-singular");
        let mut x = [C64::new(0.0, 0.0); 3];
        assert!(solve_shifted_transpose(&a, &c, -3.0, &mut x));
        assert_eq!(x.to_vec(), want, "the values");
        assert_eq!(bits(&x), bits(&want));
        assert!(x[1].im == 0.0 && x[1].im.is_sign_negative() && !want[1].im.is_sign_negative());
        let zero = DMatrix::zeros(3, 3);
        assert_eq!(nalgebra_row(&zero, &[1.0, 2.0, 3.0], 0.0), None);
        assert!(!solve_shifted_transpose(
            &zero,
            &[1.0, 2.0, 3.0],
            0.0,
            &mut [C64::new(0.0, 0.0); 3]
        ));
        assert_eq!(cases, (16 * 60 + (SHIFTED_MAX - 16) * 4) * 5);
    }
}
