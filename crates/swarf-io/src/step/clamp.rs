//! Clamping an unclamped (periodic or uniform) B-spline direction, as STEP writes
//! periodic surfaces, into the clamped form [`swarf_geom::Patch::new`] requires.
//!
//! The surface lives on `[U_p, U_n]` (`n` control points per row). Inserting the
//! knot `a = U_p` until it has multiplicity `p` (Boehm's algorithm, NURBS Book
//! section 5.2, on homogeneous points so rational rows stay exact) makes the curve
//! pass through one control point at `a`; the knots and points before it no longer
//! influence `[a, ...)` and are dropped, `a` taking multiplicity `p + 1`. The end is
//! clamped the same way on the reversed knots.

/// Homogeneous control point `(x w, y w, z w, w)`.
pub type Hom = [f64; 4];

/// Inserts knot `t` once (Boehm).
fn insert(p: usize, knots: &mut Vec<f64>, pts: &mut Vec<Hom>, t: f64) {
    let k = knots
        .iter()
        .rposition(|u| *u <= t)
        .unwrap_or(0)
        .min(pts.len() - 1);
    let mut q = Vec::with_capacity(pts.len() + 1);
    for i in 0..=pts.len() {
        if i + p <= k {
            q.push(pts[i]);
        } else if i > k {
            q.push(pts[i - 1]);
        } else {
            let den = knots[i + p] - knots[i];
            let a = if den > 0.0 { (t - knots[i]) / den } else { 0.0 };
            let mut r = [0.0; 4];
            for (c, rc) in r.iter_mut().enumerate() {
                *rc = a * pts[i][c] + (1.0 - a) * pts[i - 1][c];
            }
            q.push(r);
        }
    }
    knots.insert(k + 1, t);
    *pts = q;
}

/// Clamps the start: `U_p` with multiplicity `p + 1` at the front.
fn clamp_start(p: usize, knots: &mut Vec<f64>, pts: &mut Vec<Hom>) {
    let a = knots[p];
    let s = knots.iter().filter(|u| **u == a).count();
    for _ in s..p {
        insert(p, knots, pts, a);
    }
    let i0 = knots.iter().position(|u| *u == a).unwrap_or(0);
    if i0 == 0 {
        return;
    }
    knots.drain(..i0 - 1);
    knots[0] = a;
    pts.drain(..i0 - 1);
}

/// Clamps both ends of one row; returns `None` when the row is too short.
pub fn clamp(p: usize, knots: &[f64], pts: &[Hom]) -> Option<(Vec<f64>, Vec<Hom>)> {
    if p == 0 || pts.len() <= p || knots.len() != pts.len() + p + 1 {
        return None;
    }
    let mut k = knots.to_vec();
    let mut q = pts.to_vec();
    clamp_start(p, &mut k, &mut q);
    let mut rk: Vec<f64> = k.iter().rev().map(|u| -u).collect();
    q.reverse();
    clamp_start(p, &mut rk, &mut q);
    q.reverse();
    let k = rk.iter().rev().map(|u| -u).collect();
    Some((k, q))
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_geom::{NurbsCurve, Point3};

    #[test]
    fn clamped_curve_equals_the_unclamped_one() {
        let pts = [
            [0.0, 0.0, 0.0, 1.0],
            [2.0, 4.0, 0.0, 2.0],
            [6.0, 3.0, 1.5, 1.5],
            [4.0, -2.0, 0.0, 1.0],
            [-1.0, 1.0, 2.0, 0.5],
            [3.0, 3.0, 3.0, 1.0],
        ];
        let p = 3;
        let knots: Vec<f64> = (0..pts.len() + p + 1)
            .map(|i| f64::from(i as u32) * 0.5)
            .collect();
        let curve = |k: Vec<f64>, q: &[Hom]| {
            let points = q
                .iter()
                .map(|h| Point3::new(h[0] / h[3], h[1] / h[3], h[2] / h[3]))
                .collect();
            NurbsCurve::new(p, k, points, Some(q.iter().map(|h| h[3]).collect())).unwrap()
        };
        let a = curve(knots.clone(), &pts);
        let (ck, cq) = clamp(p, &knots, &pts).unwrap();
        assert!(ck[..=p].iter().all(|u| *u == ck[0]));
        assert!(
            ck[ck.len() - p - 1..]
                .iter()
                .all(|u| *u == ck[ck.len() - 1])
        );
        let b = curve(ck, &cq);
        assert_eq!(a.domain(), b.domain());
        let [t0, t1] = a.domain();
        for i in 0..=50 {
            let t = t0 + (t1 - t0) * f64::from(i) / 50.0;
            assert!((a.eval(t) - b.eval(t)).norm() < 1e-12, "t {t}");
        }
        assert!(clamp(3, &knots[..5], &pts[..2]).is_none());
    }
}
