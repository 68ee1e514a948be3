//! Clamping a B-spline direction at the ends of its domain `[U_p, U_n]` (`n` control
//! points, degree `p`) by knot insertion, the surface unchanged (The NURBS Book sec.
//! 5.2, eq. 5.15; periodic and unclamped knots as STEP and IGES write them). The one
//! clamp of both CAD readers.
//!
//! Inserting `a = U_p` until its multiplicity is `p` makes the curve pass through
//! the control point just before the run of `a`s, `P_{f-1}` (`f` its first index);
//! the knots before the run and the points before `P_{f-1}` then only shape the
//! curve outside the domain and are dropped, and one more `a` completes the clamp.
//! The end `b = U_n` is treated the same way, mirrored. Each "control point" here is
//! a whole row of the homogeneous net (`w x, w y, w z, w` of every point across the
//! other direction), so one pass clamps every iso-curve at once.

/// Clamps `knots` (`rows.len() + p + 1` of them) and the `rows` of homogeneous
/// coordinates in place. Knots already clamped are left as they are. `None` (and
/// nothing changed) when the counts do not fit: degree 0, no more rows than `p`, or
/// a knot count other than `rows.len() + p + 1`.
pub(crate) fn clamp(p: usize, knots: &mut Vec<f64>, rows: &mut Vec<Vec<f64>>) -> Option<()> {
    if p == 0 || rows.len() <= p || knots.len() != rows.len() + p + 1 {
        return None;
    }
    let all_eq = |s: &[f64]| s.iter().all(|x| *x == s[0]);
    if !all_eq(&knots[..=p]) {
        let a = knots[p];
        raise(p, a, knots, rows);
        let f = knots.iter().position(|x| *x == a).unwrap_or(0);
        let run = knots[f..].iter().take_while(|x| **x == a).count();
        if run > p || f == 0 {
            knots.drain(..f);
            rows.drain(..f);
        } else {
            knots.drain(..f - 1);
            knots[0] = a;
            rows.drain(..f - 1);
        }
    }
    let len = knots.len();
    if !all_eq(&knots[len - p - 1..]) {
        let b = knots[rows.len()];
        raise(p, b, knots, rows);
        let l = knots.iter().rposition(|x| *x == b).unwrap_or(0);
        let run = knots[..=l].iter().rev().take_while(|x| **x == b).count();
        if run > p {
            knots.truncate(l + 1);
            rows.truncate(l - p);
        } else {
            knots.truncate(l + 1);
            knots.push(b);
            rows.truncate(l - p + 1);
        }
    }
    Some(())
}

/// Inserts `t` until its multiplicity is at least `p`.
fn raise(p: usize, t: f64, knots: &mut Vec<f64>, rows: &mut Vec<Vec<f64>>) {
    for _ in 0..=p {
        let s = knots.iter().filter(|x| **x == t).count();
        if s >= p {
            return;
        }
        insert(p, t, s, knots, rows);
    }
}

/// Boehm's insertion of `t` (multiplicity `s`) once.
fn insert(p: usize, t: f64, s: usize, knots: &mut Vec<f64>, rows: &mut Vec<Vec<f64>>) {
    let n = rows.len();
    let Some(k) = (p..knots.len() - 1)
        .rev()
        .find(|&k| knots[k] <= t && knots[k + 1] > t)
        .filter(|&k| k >= s && k - s < n)
    else {
        return;
    };
    let mut out = Vec::with_capacity(n + 1);
    for i in 0..=n {
        if i + p <= k {
            out.push(rows[i].clone());
        } else if i + s > k {
            out.push(rows[i - 1].clone());
        } else {
            let a = (t - knots[i]) / (knots[i + p] - knots[i]);
            let row = rows[i]
                .iter()
                .zip(&rows[i - 1])
                .map(|(x, y)| a * x + (1.0 - a) * y)
                .collect();
            out.push(row);
        }
    }
    knots.insert(k + 1, t);
    *rows = out;
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_geom::{NurbsCurve, Point3};

    /// A periodic cubic clamped gives the same curve (oracle: the unclamped curve
    /// evaluated by NurbsCurve, which accepts unclamped knots).
    #[test]
    fn clamping_keeps_the_curve() {
        let knots: Vec<f64> = (0..11).map(|k| k as f64 * 0.5 - 1.0).collect();
        let pts: Vec<Point3> = (0..7)
            .map(|k| Point3::new(k as f64, ((k * 7) % 5) as f64, ((k * 3) % 4) as f64))
            .collect();
        let w: Vec<f64> = (0..7).map(|k| 1.0 + 0.25 * (k % 3) as f64).collect();
        let orig = NurbsCurve::new(3, knots.clone(), pts.clone(), Some(w.clone())).unwrap();
        let mut rows: Vec<Vec<f64>> = pts
            .iter()
            .zip(&w)
            .map(|(p, w)| vec![w * p.x, w * p.y, w * p.z, *w])
            .collect();
        let mut k = knots;
        clamp(3, &mut k, &mut rows);
        assert_eq!(k.len(), rows.len() + 4, "{k:?}");
        assert!(k[..4].iter().all(|x| *x == 0.5) && k[k.len() - 4..].iter().all(|x| *x == 2.5));
        let p2 = rows
            .iter()
            .map(|r| Point3::new(r[0] / r[3], r[1] / r[3], r[2] / r[3]))
            .collect();
        let w2 = rows.iter().map(|r| r[3]).collect();
        let clamped = NurbsCurve::new(3, k, p2, Some(w2)).unwrap();
        assert_eq!(clamped.domain(), orig.domain());
        for s in 0..=50 {
            let t = 0.5 + 2.0 * s as f64 / 50.0;
            assert!((clamped.eval(t) - orig.eval(t)).norm() < 1e-12, "t = {t}");
        }
    }
}
