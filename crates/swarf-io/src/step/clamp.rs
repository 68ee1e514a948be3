//! Clamping an unclamped (periodic or uniform) B-spline direction, as STEP writes
//! periodic curves and surfaces, into the clamped form [`swarf_geom::Patch::new`]
//! requires: one row of homogeneous points through the readers' one clamp
//! ([`crate::clamp`]).

/// Homogeneous control point `(x w, y w, z w, w)`.
pub type Hom = [f64; 4];

/// Clamps both ends of one row; returns `None` when the row is too short.
pub fn clamp(p: usize, knots: &[f64], pts: &[Hom]) -> Option<(Vec<f64>, Vec<Hom>)> {
    let mut k = knots.to_vec();
    let mut rows: Vec<Vec<f64>> = pts.iter().map(|h| h.to_vec()).collect();
    crate::clamp::clamp(p, &mut k, &mut rows)?;
    let q = rows.iter().map(|r| [r[0], r[1], r[2], r[3]]).collect();
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
