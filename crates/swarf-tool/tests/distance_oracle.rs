//! The exact signed distance against a brute-force oracle built only from
//! `surface_point` (dense samples of the cutting surface plus the top disc).
//!
//! Magnitude: the nearest sample is at most the sampling radius farther than the true
//! nearest point. Sign, for convex tools (beta >= 0): a point is inside exactly when it
//! lies below every sampled tangent plane.

mod common;

use common::{all_cutters, boundary_samples, spherical};
use swarf_geom::Point3;
use swarf_tool::Pose;

#[test]
fn signed_distance_matches_dense_sampling() {
    let (ns, nr, nphi) = (600, 80, 360);
    let mut checked_inside = 0;
    for (index, cutter) in all_cutters().into_iter().enumerate() {
        let profile = cutter.profile();
        let pose = Pose::new(
            Point3::new(3.0, -1.0, 2.0),
            spherical(0.3 + 0.4 * index as f64, 1.1 * index as f64),
        )
        .unwrap();
        let samples = boundary_samples(&profile, &pose, ns, nr, nphi);
        // Sampling radius: half the largest gap between neighbouring samples.
        let step_s = profile.arc_length() / ns as f64;
        let step_phi = profile.radius() * std::f64::consts::TAU / nphi as f64;
        let step_r = profile.top().rho / nr as f64;
        let gap = 0.5 * step_s.max(step_r).hypot(step_phi);
        let convex = cutter.to_apt().beta >= 0.0;
        let (r, h) = (profile.radius(), profile.length());
        for k in 0..40 {
            let t = k as f64;
            let p = pose.cl
                + (r + 2.0)
                    * (0.1 + 0.9 * (t * 0.61).sin().abs())
                    * spherical(1.0 + 1.4 * (t * 1.3).sin(), t * 2.399)
                + (h * 0.5 * (1.0 + (t * 0.77).sin())) * pose.axis;
            let exact = profile.signed_distance(&pose, &p);
            let nearest = samples
                .iter()
                .map(|(q, _)| (p - q).norm())
                .fold(f64::INFINITY, f64::min);
            assert!(
                nearest >= exact.abs() - 1e-9 && nearest <= exact.abs() + gap,
                "{cutter}: at {p}: exact {exact}, sampled {nearest} (gap {gap})"
            );
            if convex && exact.abs() > 2.0 * gap {
                let outside = samples.iter().any(|(q, n)| (p - q).dot(n) > 0.0);
                assert_eq!(outside, exact > 0.0, "{cutter}: sign at {p}: {exact}");
                checked_inside += usize::from(exact < 0.0);
            }
        }
    }
    assert!(
        checked_inside > 20,
        "too few inside points: {checked_inside}"
    );
}
