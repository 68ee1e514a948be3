//! Shared fixtures for the integration tests: a spread of cutters and a dense sampler
//! of the tool boundary (an oracle that uses only `surface_point`).

#![allow(dead_code)]

use swarf_geom::{Point3, Vec3};
use swarf_tool::{Cutter, Pose, Profile};

/// Named shapes, including the degenerate bulls (r = 0, r = d/2).
pub const NAMED: &[&str] = &[
    "flat:d=6,length=12",
    "ball:d=8,length=12",
    "bull:d=10,r=2,length=12",
    "bull:d=10,r=0,length=12",
    "bull:d=10,r=5,length=12",
    "cone:d=10,angle=90,length=12",
    "cone:d=6,angle=30,length=15",
    "taperball:d=6,angle=10,tip=1",
    "taperball:d=4,angle=3,tip=0.5,length=8",
    "taperball:d=6,angle=0,tip=2,length=10",
];

/// General APT tools: a rounded corner, a sharp corner, an undercut (beta < 0).
pub const GENERAL: &[&str] = &[
    "apt:d=10,r=1.5,alpha=10,beta=5,h=12",
    "apt:d=10,r=0,alpha=20,beta=10,h=10",
    "apt:d=8,r=2,alpha=30,beta=0,h=10",
    "apt:d=10,r=1,alpha=5,beta=-10,h=8",
];

pub fn cutter(spec: &str) -> Cutter {
    spec.parse().unwrap_or_else(|e| panic!("{spec}: {e}"))
}

pub fn all_cutters() -> Vec<Cutter> {
    NAMED.iter().chain(GENERAL).map(|s| cutter(s)).collect()
}

/// Unit vector from spherical angles (polar from +z, azimuth).
pub fn spherical(polar: f64, azimuth: f64) -> Vec3 {
    let (sp, cp) = polar.sin_cos();
    let (sa, ca) = azimuth.sin_cos();
    Vec3::new(sp * ca, sp * sa, cp)
}

/// Boundary samples with outward normals: the cutting surface on an `ns x nphi`
/// grid plus the top disc on `nr x nphi`.
pub fn boundary_samples(
    profile: &Profile,
    pose: &Pose,
    ns: usize,
    nr: usize,
    nphi: usize,
) -> Vec<(Point3, Vec3)> {
    let mut out = Vec::with_capacity((ns + nr + 2) * nphi);
    let top = profile.top();
    for j in 0..nphi {
        let phi = j as f64 * std::f64::consts::TAU / nphi as f64;
        for i in 0..=ns {
            out.push(profile.surface_point(pose, i as f64 / ns as f64, phi));
        }
        let (rim, _) = profile.surface_point(pose, 1.0, phi);
        let centre = pose.cl + top.z * pose.axis;
        for i in 0..=nr {
            let t = i as f64 / nr as f64;
            out.push((centre + t * (rim - centre), pose.axis));
        }
    }
    out
}
