//! pose_from_contact / contact_from_pose for random normals and (five-axis) tool axes:
//! the tool touches the CC point with the matching normal and never crosses the
//! tangent plane there.

mod common;

use common::{all_cutters, spherical};
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, TAU};
use swarf_geom::{Point3, Vec3};
use swarf_tool::pose::reference_frame;

/// The surface normal `n` for which the tool's outward normal is at profile angle
/// `psi`, azimuth `phi` around `axis`.
fn normal_for(axis: &Vec3, psi: f64, phi: f64) -> Vec3 {
    let (b1, b2) = reference_frame(axis);
    let u = phi.cos() * b1 + phi.sin() * b2;
    -(psi.cos() * u + psi.sin() * axis)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn contact_roundtrip_touches_without_crossing(
        which in 0usize..14,
        polar in 0.0..std::f64::consts::PI,
        azimuth in 0.0..TAU,
        t in 0.0..=1.0f64,
        phi in 0.0..TAU,
        x in -50.0..50.0f64, y in -50.0..50.0f64, z in -50.0..50.0f64,
    ) {
        let cutters = all_cutters();
        let cutter = cutters[which % cutters.len()];
        let axis = spherical(polar, azimuth);
        let beta = cutter.to_apt().beta;
        let psi = -FRAC_PI_2 + t * (FRAC_PI_2 - beta);
        let n = normal_for(&axis, psi, phi);
        let cc = Point3::new(x, y, z);

        let pose = cutter.pose_from_contact(&cc, &n, &axis).expect("a valid normal has a pose");
        prop_assert!((pose.axis - axis).norm() < 1e-12);
        let back = cutter.contact_from_pose(&pose, &n).expect("and a contact");
        prop_assert!((back - cc).norm() < 1e-9, "round trip {back} vs {cc}");
        let offset = cutter.cl_offset(&n, &axis).unwrap();
        prop_assert!((pose.cl - (cc + offset)).norm() < 1e-12);
        prop_assert!(cutter.signed_distance(&pose, &cc).abs() < 1e-9);

        // The surface point at the contact's parameters is the CC point, and off a
        // sharp corner its normal is -n.
        let profile = cutter.profile();
        let (contact, u) = profile.contact_for_normal(&n, &axis).unwrap();
        let (b1, b2) = reference_frame(&axis);
        let phi_c = u.dot(&b2).atan2(u.dot(&b1));
        let (q, m) = profile.surface_point(&pose, contact.s, phi_c);
        prop_assert!((q - cc).norm() < 1e-9, "surface point {q} vs {cc}");
        if !contact.corner {
            prop_assert!((m + n).norm() < 1e-9, "normal {m} vs {}", -n);
        }

        // No point of the cutting surface lies below the tangent plane.
        let ns = 160;
        let nphi = 120;
        let mut lowest = f64::INFINITY;
        for j in 0..nphi {
            let ph = phi_c + j as f64 * TAU / nphi as f64;
            for i in 0..=ns {
                let s = (contact.s + i as f64 / ns as f64) % 1.0;
                let (p, _) = profile.surface_point(&pose, s, ph);
                lowest = lowest.min((p - cc).dot(&n));
            }
        }
        prop_assert!(lowest > -1e-9, "tool crosses the tangent plane by {}", -lowest);
        prop_assert!(lowest < 1e-9);
    }

    #[test]
    fn normals_facing_the_top_have_no_pose(
        which in 0usize..14,
        polar in 0.0..std::f64::consts::PI,
        azimuth in 0.0..TAU,
        t in 0.001..=1.0f64,
        phi in 0.0..TAU,
    ) {
        let cutters = all_cutters();
        let cutter = cutters[which % cutters.len()];
        let axis = spherical(polar, azimuth);
        let beta = cutter.to_apt().beta;
        let psi = -beta + t * (FRAC_PI_2 + beta);
        let n = normal_for(&axis, psi, phi);
        prop_assert!(cutter.pose_from_contact(&Point3::origin(), &n, &axis).is_none());
    }
}
