//! The machined surface of a tool path as a mesh of generating curves (thesis 000
//! §3.3.1 and §5.4.2: corresponding points of consecutive generating curves "joined
//! with straight lines").
//!
//! Along a pass, each half of the tool gives one generating curve per pose
//! ([`crate::gencurve`]). Consecutive curves have the same layout and are joined point
//! by point into strips of triangles: the ruled surface of the lines between
//! corresponding inserts or cards. The first and last poses add the tool's
//! lower surface up to the wall height (the thesis adds the back half at the start and
//! the front half at the end; the whole tool is added here because the tool also comes
//! down and leaves along its axis there).
//!
//! The machined surface at `(x, y)` is the lowest point of the mesh above it (a
//! vertical ray through the union of the swept volumes' lower boundaries), found with
//! the height-field query of swarf-geom ([`MeshHeights::lower`]); sampling it along a line on a section plane gives the
//! section profiles that the thesis compares with measurements and with the Z-map.

use crate::gencurve::{CurveOptions, Half, PoseCurve};
use crate::sections::Sections;
use swarf_geom::height::MeshHeights;
use swarf_geom::{GeomError, MeshBuilder, Point3, TriMesh, Vec3};
use swarf_tool::{Pose, Profile, ProfileTable};

/// Twice a triangle's area below which it is dropped from the mesh (mm^2).
const MIN_DOUBLE_AREA: f64 = 1e-12;
/// Chords per profile arc in the end caps.
const CAP_ARC_PIECES: usize = 64;
/// Meridians around the axis in the end caps.
const CAP_MERIDIANS: usize = 360;

/// The machined surface of one or more passes.
#[derive(Debug, Clone)]
pub struct SweptSurface {
    surface: MeshHeights<'static>,
}

impl SweptSurface {
    /// The swept surface of the passes (each a list of poses with unit axes).
    ///
    /// # Errors
    /// [`GeomError::InvalidMesh`] when a pose is not finite.
    pub fn new(
        profile: &Profile,
        passes: &[Vec<Pose>],
        opts: &CurveOptions,
    ) -> Result<SweptSurface, GeomError> {
        let mut b = MeshBuilder::new();
        let table = ProfileTable::new(profile);
        for poses in passes {
            add_pass(&mut b, &table, poses, opts)?;
        }
        Ok(SweptSurface {
            surface: MeshHeights::owned(b.finish()),
        })
    }

    /// The surface as triangles (mm).
    pub fn mesh(&self) -> &TriMesh {
        self.surface.mesh()
    }

    /// The lowest point of the swept surface above `(x, y)`: the machined height there;
    /// `None` where the tool never passed.
    ///
    /// # Units
    /// mm.
    pub fn height(&self, x: f64, y: f64) -> Option<f64> {
        self.surface.lower(x, y)
    }

    /// The machined surface sampled at `points` (their z is ignored): one height per
    /// point, `None` where the tool never passed.
    pub fn heights(&self, points: &[Point3]) -> Vec<Option<f64>> {
        points.iter().map(|p| self.height(p.x, p.y)).collect()
    }

    /// The machined surface on the vertical plane `k` of `sections`, sampled every
    /// `step` mm along it across the surface's extent: the section profile the thesis
    /// compares with measurements (points where the tool never passed are left out).
    ///
    /// # Units
    /// mm.
    pub fn section(&self, sections: &Sections, k: i64, step: f64) -> Vec<Point3> {
        let b = self.mesh().aabb();
        if b.is_empty() || !(step.is_finite() && step > 0.0) {
            return Vec::new();
        }
        let n = sections.normal;
        let along = Vec3::new(-n.y, n.x, 0.0);
        let origin = n * sections.value(k);
        let corners =
            [b.min.x, b.max.x].map(|x| [b.min.y, b.max.y].map(|y| along.x * x + along.y * y));
        let flat = corners.iter().flatten();
        let t0 = flat.clone().fold(f64::INFINITY, |a, &t| a.min(t));
        let t1 = flat.fold(f64::NEG_INFINITY, |a, &t| a.max(t));
        let count = ((t1 - t0) / step).ceil().min(1e7) as usize;
        (0..=count)
            .filter_map(|j| {
                let t = t0 + j as f64 * step;
                let (x, y) = (origin.x + t * along.x, origin.y + t * along.y);
                self.height(x, y).map(|z| Point3::new(x, y, z))
            })
            .collect()
    }
}

fn add_pass(
    b: &mut MeshBuilder,
    table: &ProfileTable<'_>,
    poses: &[Pose],
    opts: &CurveOptions,
) -> Result<(), GeomError> {
    let profile = table.profile();
    let top = opts
        .wall_height
        .unwrap_or_else(|| profile.full_radius_height())
        .min(profile.top().z);
    if let Some(first) = poses.first() {
        add_cap(b, profile, first, top)?;
    }
    if poses.len() > 1
        && let Some(last) = poses.last()
    {
        add_cap(b, profile, last, top)?;
    }
    for half in [Half::Front, Half::Back] {
        let mut prev: Option<Vec<Point3>> = None;
        for i in 0..poses.len() {
            let curve = PoseCurve::new(table, poses, i, half, *opts).curve();
            if let Some(p) = &prev {
                add_strip(b, p, &curve)?;
            }
            prev = Some(curve);
        }
    }
    Ok(())
}

fn add_strip(b: &mut MeshBuilder, c0: &[Point3], c1: &[Point3]) -> Result<(), GeomError> {
    for j in 0..c0.len().min(c1.len()).saturating_sub(1) {
        add_triangle(b, [c0[j], c0[j + 1], c1[j + 1]])?;
        add_triangle(b, [c0[j], c1[j + 1], c1[j]])?;
    }
    Ok(())
}

fn add_triangle(b: &mut MeshBuilder, t: [Point3; 3]) -> Result<(), GeomError> {
    if (t[1] - t[0]).cross(&(t[2] - t[0])).norm() > MIN_DOUBLE_AREA {
        b.push_triangle(t)?;
    }
    Ok(())
}

/// The tool's surface at `pose` from the tip up to height `top`, revolved.
fn add_cap(b: &mut MeshBuilder, profile: &Profile, pose: &Pose, top: f64) -> Result<(), GeomError> {
    let meridian = profile.polyline(CAP_ARC_PIECES, top);
    let (b1, b2) = pose.frame();
    let ring = |m: usize| -> Vec<Point3> {
        let (s, c) = (std::f64::consts::TAU * m as f64 / CAP_MERIDIANS as f64).sin_cos();
        let u = c * b1 + s * b2;
        meridian
            .iter()
            .map(|q| pose.cl + q.rho * u + q.z * pose.axis)
            .collect()
    };
    let mut prev = ring(0);
    for m in 1..=CAP_MERIDIANS {
        let next = ring(m % CAP_MERIDIANS);
        add_strip(b, &prev, &next)?;
        prev = next;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_tool::Cutter;

    #[test]
    fn straight_bull_pass_leaves_its_profile() {
        // A vertical bull (d 10, r 2) moving along +y at z = 0: across the pass the
        // machined surface is the tool's profile, flat for |x| <= 3, then the corner.
        let profile = Cutter::bull(10.0, 2.0, Some(20.0)).unwrap().profile();
        let poses: Vec<Pose> = (0..=10)
            .map(|i| Pose::vertical(Point3::new(0.0, i as f64, 0.0)))
            .collect();
        let opts = CurveOptions {
            wall_cards: 16,
            ..CurveOptions::default()
        };
        let s = SweptSurface::new(&profile, &[poses], &opts).unwrap();
        for x in [-2.9, -1.0, 0.0, 0.7, 2.5] {
            let z = s.height(x, 5.3).unwrap();
            assert!(z.abs() < 1e-9, "x {x}: {z}");
        }
        for x in [3.5f64, 4.0, 4.6, -4.2] {
            let expected = 2.0 - (4.0 - (x.abs() - 3.0).powi(2)).sqrt();
            let z = s.height(x, 5.3).unwrap();
            // Chords of 16 cards over the quarter arc of radius 2: sagitta 2 (1 -
            // cos(pi / 64)) = 2.4 um, more in z where the arc is steep.
            assert!((z - expected).abs() < 0.006, "x {x}: {z} vs {expected}");
        }
        assert!(s.height(0.0, 20.0).is_none());
        assert!(s.height(6.0, 5.0).is_none());
        assert!(!s.mesh().is_empty());
        // The section y = 5.3 across the pass is the tool's profile; x = 1 along it is
        // flat from the first to the last pose.
        let across = Sections::along(0.0, 5.3).unwrap();
        let prof = s.section(&across, 1, 0.25);
        assert!(
            prof.iter()
                .all(|p| (p.y - 5.3).abs() < 1e-12 && p.x.abs() <= 5.0 + 1e-9)
        );
        assert!(prof.len() >= 38, "{}", prof.len());
        let along = Sections::along(std::f64::consts::FRAC_PI_2, 1.0).unwrap();
        let flat = s.section(&along, -1, 0.5);
        let within: Vec<_> = flat
            .iter()
            .filter(|p| (0.0..=10.0).contains(&p.y))
            .collect();
        assert!(
            within
                .iter()
                .all(|p| p.z.abs() < 1e-9 && (p.x - 1.0).abs() < 1e-12)
        );
        assert!(within.len() >= 20, "{}", within.len());
    }
}
