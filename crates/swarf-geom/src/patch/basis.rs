//! Knot-span search and B-spline basis functions with their first two derivatives.
//!
//! The span search is The NURBS Book's A2.1 (binary search for the `k` with
//! `U_k <= t < U_{k+1}`, the last non-empty span at the right end). The basis functions
//! of degree `p` come from the Cox-de Boor triangle of A2.2, kept on the stack:
//! `N_{i,j}(t) = (t - U_i)/(U_{i+j} - U_i) N_{i,j-1}(t) + (U_{i+j+1} - t)/(U_{i+j+1} - U_{i+1})
//! N_{i+1,j-1}(t)`. The triangle passes through degrees `p - 2` and `p - 1` on its way to
//! `p`; we keep those rows and differentiate with the derivative recurrence (eq. 2.7,
//! the idea of A2.3 restricted to two orders):
//!
//! `N'_{i,q} = q N_{i,q-1}/(U_{i+q} - U_i) - q N_{i+1,q-1}/(U_{i+q+1} - U_{i+1})`,
//!
//! applied once for `N'_{.,p}` (from degree `p - 1`), and twice for `N''_{.,p}` (first
//! `N'_{.,p-1}` from degree `p - 2`, then the same recurrence on those derivatives, since
//! the recurrence is linear). Every denominator is a knot interval that covers the
//! non-empty span, so none is zero. Arrays are fixed at [`MAX_ORDER`] entries: nothing
//! is allocated.

/// Largest degree a patch may have in either direction ([`crate::Patch::new`] checks it).
pub const MAX_DEGREE: usize = 15;
/// Largest number of basis functions non-zero on one span (`MAX_DEGREE + 1`).
pub const MAX_ORDER: usize = MAX_DEGREE + 1;

/// Index `k` of the non-empty knot span `[U_k, U_{k+1})` holding `t`, for degree `p`
/// on the clamped knot vector `knots` (NURBS Book A2.1).
///
/// Parameters below the range give the first span, at or above its end the last one
/// (and so does NaN: the caller's arithmetic then propagates it). The result lies in
/// `p ..= n - 1` with `n = knots.len() - p - 1` control points.
pub fn find_span(knots: &[f64], p: usize, t: f64) -> usize {
    let n = knots.len() - p - 1;
    if n == p + 1 || t <= knots[p] {
        return p;
    }
    if t.partial_cmp(&knots[n]) != Some(std::cmp::Ordering::Less) {
        return n - 1;
    }
    let (mut lo, mut hi) = (p, n);
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        if t < knots[mid] {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    lo
}

/// The `p + 1` non-zero basis functions on a span and their first two derivatives.
#[derive(Debug, Clone, Copy)]
pub struct BasisDerivs<const ORD: usize = MAX_ORDER> {
    /// The knot span index `k`; entry `r` belongs to function `N_{k-p+r, p}`.
    pub span: usize,
    /// `d[order][r]`: value (order 0), first and second derivatives of `N_{k-p+r, p}`.
    pub d: [[f64; ORD]; 3],
}

/// The `p + 1` non-zero basis functions of degree `p` at `t` on `span` (NURBS Book A2.2).
/// Entry `r` belongs to `N_{span-p+r, p}`.
pub fn basis_funs(knots: &[f64], p: usize, span: usize, t: f64) -> [f64; MAX_ORDER] {
    basis_funs_n::<MAX_ORDER>(knots, p, span, t)
}

/// Basis functions of degree `p` at `t` with their first and second derivatives.
pub fn basis_derivs(knots: &[f64], p: usize, t: f64) -> BasisDerivs {
    basis_derivs_n::<MAX_ORDER>(knots, p, t)
}

/// The degree for arrays of `ORD` entries: `ORD - 1` (a compile-time constant, so that
/// the loops unroll) when `ORD` is below [`MAX_ORDER`], else `p`.
#[inline(always)]
fn degree<const ORD: usize>(p: usize) -> usize {
    if ORD < MAX_ORDER { ORD - 1 } else { p }
}

/// [`basis_funs`] into `ORD` entries (see [`degree`]).
#[inline(always)]
pub(crate) fn basis_funs_n<const ORD: usize>(
    knots: &[f64],
    p: usize,
    span: usize,
    t: f64,
) -> [f64; ORD] {
    let p = degree::<ORD>(p);
    let mut n = [0.0; ORD];
    triangle(&knots[span + 1 - p..=span + p], p, t, &mut n, |_, _| {});
    n
}

/// [`basis_derivs`] into `ORD` entries (see [`degree`]).
#[inline(always)]
pub(crate) fn basis_derivs_n<const ORD: usize>(
    knots: &[f64],
    p: usize,
    t: f64,
) -> BasisDerivs<ORD> {
    let p = degree::<ORD>(p);
    let span = find_span(knots, p, t);
    let window = &knots[span + 1 - p..=span + p];
    let mut d = [[0.0; ORD]; 3];
    let mut lower1 = [0.0; ORD];
    let mut lower2 = [0.0; ORD];
    let [d0, d1, d2] = &mut d;
    triangle(window, p, t, d0, |j, row| {
        if j + 1 == p {
            lower1 = *row;
        } else if j + 2 == p {
            lower2 = *row;
        }
    });
    *d1 = derive(window, p, p, &lower1);
    if p >= 2 {
        let first_lower = derive(window, p, p - 1, &lower2);
        *d2 = derive(window, p, p, &first_lower);
    }
    BasisDerivs { span, d }
}

/// The Cox-de Boor triangle (A2.2) into `n`, calling `at_degree(j, row)` with the row
/// of degree `j` for `j = 0 .. p-1` before it is raised. `window` holds the knots
/// `U_{span+1-p} ..= U_{span+p}`.
#[inline(always)]
fn triangle<const ORD: usize>(
    window: &[f64],
    p: usize,
    t: f64,
    n: &mut [f64; ORD],
    mut at_degree: impl FnMut(usize, &[f64; ORD]),
) {
    let mut left = [0.0; ORD];
    let mut right = [0.0; ORD];
    n[0] = 1.0;
    for j in 1..=p {
        at_degree(j - 1, n);
        left[j] = t - window[p - j];
        right[j] = window[p - 1 + j] - t;
        let mut saved = 0.0;
        for r in 0..j {
            let temp = n[r] / (right[r + 1] + left[j - r]);
            n[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        n[j] = saved;
    }
}

/// Derivatives of the `q + 1` functions `N_{span-q+r, q}` from `lower[r]`, the values (or
/// derivatives of any order) of `N_{span-q+1+r, q-1}`, by the recurrence of eq. 2.7.
/// `window` holds `U_{span+1-p} ..= U_{span+p}` (`q <= p`), so `U_i` for
/// `i = span + r + 1 - q` is `window[r + p - q]`.
#[inline(always)]
fn derive<const ORD: usize>(window: &[f64], p: usize, q: usize, lower: &[f64; ORD]) -> [f64; ORD] {
    let mut out = [0.0; ORD];
    let qf = q as f64;
    let mut saved = 0.0;
    for r in 0..q {
        let b = lower[r] / (window[r + p] - window[r + p - q]);
        out[r] = qf * (saved - b);
        saved = b;
    }
    out[q] = qf * saved;
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Cox-de Boor by its definition, recursively, with 0/0 = 0: the oracle.
    fn cox_de_boor(k: &[f64], i: usize, p: usize, t: f64) -> f64 {
        if p == 0 {
            let last = k.iter().rposition(|x| *x < k[k.len() - 1]).unwrap_or(0);
            let inside = k[i] <= t && t < k[i + 1];
            return if inside || (t == k[k.len() - 1] && i == last) {
                1.0
            } else {
                0.0
            };
        }
        let mut s = 0.0;
        if k[i + p] > k[i] {
            s += (t - k[i]) / (k[i + p] - k[i]) * cox_de_boor(k, i, p - 1, t);
        }
        if k[i + p + 1] > k[i + 1] {
            s += (k[i + p + 1] - t) / (k[i + p + 1] - k[i + 1]) * cox_de_boor(k, i + 1, p - 1, t);
        }
        s
    }

    const KNOTS: [f64; 12] = [0.0, 0.0, 0.0, 0.0, 0.3, 0.3, 0.5, 1.2, 2.0, 2.0, 2.0, 2.0];

    #[test]
    fn span_search_finds_the_non_empty_span() {
        let p = 3;
        let cases = [
            (-1.0, 3),
            (0.0, 3),
            (0.1, 3),
            (0.3, 5),
            (0.4, 5),
            (0.5, 6),
            (1.9, 7),
            (2.0, 7),
            (5.0, 7),
        ];
        for (t, want) in cases {
            assert_eq!(find_span(&KNOTS, p, t), want, "t = {t}");
        }
        assert_eq!(find_span(&[0.0, 0.0, 1.0, 1.0], 1, 0.5), 1);
        assert_eq!(find_span(&KNOTS, p, f64::NAN), 7);
    }

    #[test]
    fn basis_matches_the_recursive_definition() {
        let p = 3;
        for s in 0..=40 {
            let t = 2.0 * f64::from(s) / 40.0;
            let span = find_span(&KNOTS, p, t);
            let n = basis_funs(&KNOTS, p, span, t);
            let sum: f64 = n[..=p].iter().sum();
            assert!((sum - 1.0).abs() < 1e-14, "partition of unity at {t}");
            for (r, got) in n[..=p].iter().enumerate() {
                let want = cox_de_boor(&KNOTS, span - p + r, p, t);
                assert!((got - want).abs() < 1e-14, "t {t} r {r}: {got} vs {want}");
            }
        }
    }

    #[test]
    fn derivatives_match_central_differences() {
        for p in 1..=3 {
            let k: Vec<f64> = KNOTS[3 - p..KNOTS.len() - 3 + p].to_vec();
            for t in [0.05, 0.2, 0.41, 0.77, 1.5, 1.95] {
                let b = basis_derivs(&k, p, t);
                let h = 1e-5;
                let at = |x: f64| basis_funs(&k, p, b.span, x);
                let (lo, mid, hi) = (at(t - h), at(t), at(t + h));
                for r in 0..=p {
                    let d1 = (hi[r] - lo[r]) / (2.0 * h);
                    let d2 = (hi[r] - 2.0 * mid[r] + lo[r]) / (h * h);
                    assert!((b.d[0][r] - mid[r]).abs() < 1e-15);
                    assert!((b.d[1][r] - d1).abs() < 1e-6, "p {p} t {t} r {r}");
                    assert!((b.d[2][r] - d2).abs() < 1e-3, "p {p} t {t} r {r}");
                }
                let s1: f64 = b.d[1][..=p].iter().sum();
                let s2: f64 = b.d[2][..=p].iter().sum();
                assert!(s1.abs() < 1e-12 && s2.abs() < 1e-9, "derivatives of unity");
            }
        }
    }

    #[test]
    fn bernstein_second_derivatives_are_exact() {
        let k = [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
        let t: f64 = 0.3;
        let b = basis_derivs(&k, 3, t);
        let s = 1.0 - t;
        let want = [6.0 * s, -12.0 * s + 6.0 * t, 6.0 * s - 12.0 * t, 6.0 * t];
        for (r, w) in want.iter().enumerate() {
            assert!((b.d[2][r] - w).abs() < 1e-13, "r {r}");
        }
    }
}
