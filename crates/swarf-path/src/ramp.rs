//! The ramp-limited CL profile of a pass, and its ramp points (thesis 002 §3.1.3).
//!
//! A ramp angle limit `theta` lets the tool climb or descend at most `k = tan theta`
//! per unit of travel. Along a pass with CL heights `z_i` at arc lengths `s_i`, the
//! lowest profile that never dips below any sample and never slopes more than `k` is
//! the upper envelope of the cones from the samples:
//! `l_i = max_j (z_j - k |s_i - s_j|)`, computed in two sweeps (forward
//! `f_i = max(z_i, f_(i-1) - k (s_i - s_(i-1)))`, the same backward, `l = max(f, b)`).
//! It is `k`-Lipschitz, so the straight moves between samples keep the limit, and at
//! least the drop height at every sample, so it gouges no more than the unlimited
//! pass. Where it stands above the part by more than the tolerance the tool no longer
//! touches: that run is ramp rest, between the *ramp points*, the contacts of the
//! last touching samples before and after it. Each run gives a pair of ramp points
//! ([`DoubleContact`] with `ramp` set), the CL point of the largest lift and the lift
//! as its gap.

use crate::plan::DoubleContact;
use swarf_geom::Vec3;
use swarf_toolpath::PathPoint;

/// Limits the slope of `points` (a pass in travel order) to `slope` (`tan` of the
/// ramp angle) and returns the ramp-point pairs of the runs lifted by more than
/// `tol` (module doc); `pass` is the pass index they are filed under.
pub fn limit_ramp(
    points: &mut [PathPoint],
    slope: f64,
    tol: f64,
    pass: usize,
) -> Vec<DoubleContact> {
    let n = points.len();
    if n < 2 {
        return Vec::new();
    }
    let mut s = vec![0.0; n];
    for i in 1..n {
        let (a, b) = (points[i - 1].pose.cl, points[i].pose.cl);
        s[i] = s[i - 1] + (b.x - a.x).hypot(b.y - a.y);
    }
    let z: Vec<f64> = points.iter().map(|p| p.pose.cl.z).collect();
    let mut lim = z.clone();
    for i in 1..n {
        lim[i] = lim[i].max(lim[i - 1] - slope * (s[i] - s[i - 1]));
    }
    for i in (0..n - 1).rev() {
        lim[i] = lim[i].max(lim[i + 1] - slope * (s[i + 1] - s[i]));
    }
    let original: Vec<PathPoint> = points.to_vec();
    let mut out = Vec::new();
    let mut i = 0;
    while i < n {
        if lim[i] - z[i] <= tol {
            i += 1;
            continue;
        }
        let start = i;
        while i < n && lim[i] - z[i] > tol {
            i += 1;
        }
        out.extend(ramp_pair(&original, &lim, start, i, pass));
    }
    for (p, l) in points.iter_mut().zip(&lim) {
        if *l > p.pose.cl.z {
            p.lifted = *l - p.pose.cl.z;
            p.pose.cl.z = *l;
            p.contact = None;
        }
    }
    out
}

/// The ramp points around the lifted run `start..end` of `points` (heights `lim`).
fn ramp_pair(
    points: &[PathPoint],
    lim: &[f64],
    start: usize,
    end: usize,
    pass: usize,
) -> Option<DoubleContact> {
    let before = points[..start].iter().rev().find_map(|p| p.contact)?;
    let after = points[end..].iter().find_map(|p| p.contact)?;
    let (k, lift) = (start..end)
        .map(|k| (k, lim[k] - points[k].pose.cl.z))
        .fold(
            (start, f64::NEG_INFINITY),
            |m, (k, l)| if l > m.1 { (k, l) } else { m },
        );
    let mut cl = points[k].pose.cl;
    cl.z = lim[k];
    let up = |n: Vec3| if n.z < 0.0 { -n } else { n };
    Some(DoubleContact {
        cl,
        contacts: vec![before.point, after.point],
        normals: vec![up(before.normal), up(after.normal)],
        pass,
        gap: lift,
        ramp: true,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_geom::Point3;
    use swarf_tool::Pose;
    use swarf_toolpath::Contact;

    fn pass(profile: &[(f64, f64)]) -> Vec<PathPoint> {
        profile
            .iter()
            .map(|&(x, z)| PathPoint {
                pose: Pose::vertical(Point3::new(x, 0.0, z)),
                contact: Some(Contact {
                    point: Point3::new(x, 0.0, z),
                    normal: Vec3::z(),
                    face: 0,
                    uv: [f64::NAN; 2],
                }),
                lifted: 0.0,
            })
            .collect()
    }

    #[test]
    fn a_notch_is_bridged_at_the_ramp_slope() {
        // A flat pass at z = 1 with a notch 2 deep between x = 4 and x = 6.
        let xs: Vec<(f64, f64)> = (0..=20)
            .map(|i| {
                let x = f64::from(i) * 0.5;
                (x, if (4.0..=6.0).contains(&x) { -1.0 } else { 1.0 })
            })
            .collect();
        let mut p = pass(&xs);
        let pairs = limit_ramp(&mut p, 0.5, 0.01, 7);
        // Descending at 0.5 from x = 3.5 and from x = 6.5 they meet at x = 5, 0.75
        // below the top: the tool never reaches the notch's bottom.
        let z = |x: f64| p.iter().find(|q| q.pose.cl.x == x).unwrap().pose.cl.z;
        assert_eq!((z(4.0), z(5.0), z(6.0)), (0.75, 0.25, 0.75));
        for w in p.windows(2) {
            let (a, b) = (w[0].pose.cl, w[1].pose.cl);
            assert!((b.z - a.z).abs() <= 0.5 * (b.x - a.x) + 1e-12);
            assert!(b.z >= xs[p.iter().position(|q| q.pose.cl.x == b.x).unwrap()].1);
        }
        assert_eq!(pairs.len(), 1);
        let r = &pairs[0];
        assert!(r.ramp && r.pass == 7);
        assert_eq!((r.contacts[0].x, r.contacts[1].x), (3.5, 6.5));
        // The largest lift is at the notch's edges: 0.75 above its bottom at -1.
        assert_eq!((r.cl.x, r.gap), (4.0, 1.75));
        // A gentle slope is not limited.
        let mut flat = pass(&[(0.0, 0.0), (1.0, 0.2), (2.0, 0.0)]);
        assert!(limit_ramp(&mut flat, 0.5, 0.01, 0).is_empty());
        assert_eq!(flat[1].pose.cl.z, 0.2);
    }
}
