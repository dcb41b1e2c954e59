//! One row of the resolvent of a real state matrix at one frequency, c (iωI − A)⁻¹, without allocation: the
//! transposed system (iωI − Aᵀ) x = cᵀ solved on the stack by LU with partial pivoting in the steps of
//! nalgebra's `LU::new` and `LU::solve` (the same pivot choice by |re| + |im|, the same multiplier by the
//! pivot's reciprocal, the same updates in the same order, the same divisions by L's unit diagonal), so that
//! the values are those of `DMatrix::lu().solve()` on the same matrix, bit for bit
//! (`tests::the_bits_of_nalgebras_lu`): route 1's variances, and through them route 2's histograms, keep the
//! numbers of a seed. One difference in form: nalgebra's `axpy` computes y ← (a·x)·1 + 1·y, and the two unit
//! factors, exact for every finite non-zero part, are left out (y ← a·x + y); they could only turn the sign
//! of a zero part or an infinity into a NaN, which no variance reads (|H|² and sums of products with
//! non-zero weights) and only a singular system reaches. A quadrature evaluates this row at every node;
//! the heap matrices, the permutation, the solve's copy of the right-hand side and the unit factors were
//! most of its cost for the small orders of a machine model.
//!
//! # Formula
//! For k = 0 … n−1: the pivot row p ≥ k maximises |Re m_pk| + |Im m_pk| (the first such row); rows k and p
//! swap; the column below the pivot is multiplied by 1/m_kk; each later column j gets
//! m_ij ← (−m_kj)·m_ik + m_ij (i > k). A zero pivot skips the column (as nalgebra). The solve permutes cᵀ,
//! runs forward substitution with the unit diagonal (dividing by 1 + 0i) and back substitution; a zero
//! diagonal of U is a singular system (`false`).

use nalgebra::{Complex, DMatrix};

type C64 = Complex<f64>;

/// The largest order solved on the stack ([`solve_shifted_transpose`]); larger orders take nalgebra's LU.
pub const SHIFTED_MAX: usize = 16;

/// Solves (iωI − Aᵀ) x = cᵀ for a square `a` of order n ≤ [`SHIFTED_MAX`] (n ≥ 1) into `x[..n]`. Returns
/// false where nalgebra's solve returns `None` (a zero on U's diagonal); `x` then holds no meaning.
///
/// # Panics
/// If n is 0 or above [`SHIFTED_MAX`], or `c` or `x` is shorter than n (a caller's bug: the callers check).
pub fn solve_shifted_transpose(a: &DMatrix<f64>, c: &[f64], omega: f64, x: &mut [C64]) -> bool {
    let n = a.nrows();
    assert!((1..=SHIFTED_MAX).contains(&n) && a.ncols() == n && c.len() >= n && x.len() >= n);
    // one copy per order, its arrays exactly n × n (nothing to clear beyond them, loops of known length)
    macro_rules! by_order {
        ($($n:literal)*) => {
            match n {
                $($n => solve_order::<$n>(a, c, omega, &mut x[..$n]),)*
                _ => unreachable!("1 ≤ n ≤ SHIFTED_MAX"),
            }
        };
    }
    by_order!(1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16)
}

/// [`solve_shifted_transpose`] for order N.
fn solve_order<const N: usize>(a: &DMatrix<f64>, c: &[f64], omega: f64, b: &mut [C64]) -> bool {
    let s = C64::new(0.0, omega);
    let mut m = [[C64::new(0.0, 0.0); N]; N];
    for (r, row) in m.iter_mut().enumerate() {
        for (k, v) in row.iter_mut().enumerate() {
            let e = C64::new(-a[(k, r)], 0.0);
            *v = if r == k { e + s } else { e };
        }
    }
    let mut swaps = [(0usize, 0usize); N];
    let n_swaps = factor(&mut m, &mut swaps);
    for (v, &cr) in b.iter_mut().zip(c) {
        *v = C64::new(cr, 0.0);
    }
    for &(i, j) in &swaps[..n_swaps] {
        b.swap(i, j);
    }
    solve_factored(&m, b)
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

/// `LU::new` in place on `m` (m[row][column]); returns the number of row swaps recorded in `swaps`.
fn factor<const N: usize>(m: &mut [[C64; N]; N], swaps: &mut [(usize, usize); N]) -> usize {
    let n = N;
    let one = C64::new(1.0, 0.0);
    let mut n_swaps = 0;
    for i in 0..n {
        let mut piv = i;
        let mut the_max = norm1(m[i][i]);
        for (r, row) in m.iter().enumerate().skip(i + 1) {
            let val = norm1(row[i]);
            if val > the_max {
                the_max = val;
                piv = r;
            }
        }
        let diag = m[piv][i];
        if diag.re == 0.0 && diag.im == 0.0 {
            continue;
        }
        if piv != i {
            // nalgebra swaps the rows of L already computed, then the pivot column's two entries, then each
            // later column's just before its update (which reads only that column and the multipliers):
            // the whole rows at once give the same values
            swaps[n_swaps] = (i, piv);
            n_swaps += 1;
            m.swap(i, piv);
        }
        let inv_diag = one / diag;
        for row in m.iter_mut().skip(i + 1) {
            row[i] *= inv_diag;
        }
        for k in i + 1..n {
            let a = -m[i][k];
            for row in m.iter_mut().skip(i + 1) {
                row[k] = axpy_one(a, row[i], row[k]);
            }
        }
    }
    n_swaps
}

/// `LU::solve` after the permutation: forward substitution with L's unit diagonal, then back
/// substitution; false at a zero of U's diagonal.
fn solve_factored<const N: usize>(m: &[[C64; N]; N], b: &mut [C64]) -> bool {
    let n = N;
    let one = C64::new(1.0, 0.0);
    for i in 0..n - 1 {
        let coeff = b[i] / one;
        let a = -coeff;
        for r in i + 1..n {
            b[r] = axpy_one(a, m[r][i], b[r]);
        }
    }
    for i in (0..n).rev() {
        let diag = m[i][i];
        if diag.re == 0.0 && diag.im == 0.0 {
            return false;
        }
        let coeff = b[i] / diag;
        b[i] = coeff;
        let a = -coeff;
        for r in 0..i {
            b[r] = axpy_one(a, m[r][i], b[r]);
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

    fn xorshift(mut x: u64) -> impl FnMut() -> f64 {
        move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        }
    }

    fn nalgebra_row(a: &DMatrix<f64>, c: &[f64], omega: f64) -> Option<Vec<C64>> {
        solve_shifted_transpose_heap(a, c, omega).map(|x| x.iter().copied().collect())
    }

    fn bits(v: &[C64]) -> Vec<(u64, u64)> {
        v.iter().map(|z| (z.re.to_bits(), z.im.to_bits())).collect()
    }

    /// Every order 1 … SHIFTED_MAX, random matrices of mixed scales (entries spanning 10⁻⁶ … 10⁶, with
    /// exact zeros and repeated values, so that pivots tie and rows swap), frequencies from 0 up (at ω = 0
    /// every imaginary part is zero), and singular cases (a zero matrix at ω = 0, a zero row): the same
    /// bits as nalgebra's LU, the signs of zeros included, or both singular.
    #[test]
    fn the_bits_of_nalgebras_lu() {
        let mut u = xorshift(0x9E37_79B9_7F4A_7C15);
        let mut cases = 0;
        for n in 1..=SHIFTED_MAX {
            for trial in 0..60 {
                let mut a = DMatrix::from_fn(n, n, |_, _| {
                    let v = u();
                    match trial % 4 {
                        0 => v,
                        1 => v * 10f64.powf(12.0 * u()),
                        2 if v.abs() < 0.2 => 0.0,
                        3 if v.abs() < 0.25 => 1.0,
                        _ => -2.0 * v,
                    }
                });
                if trial == 59 {
                    a.row_mut(n - 1).fill(0.0);
                }
                let c: Vec<f64> = (0..n).map(|_| u()).collect();
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
        let zero = DMatrix::zeros(3, 3);
        assert_eq!(nalgebra_row(&zero, &[1.0, 2.0, 3.0], 0.0), None);
        assert!(!solve_shifted_transpose(
            &zero,
            &[1.0, 2.0, 3.0],
            0.0,
            &mut [C64::new(0.0, 0.0); 3]
        ));
        assert_eq!(cases, SHIFTED_MAX * 60 * 5);
    }
}
