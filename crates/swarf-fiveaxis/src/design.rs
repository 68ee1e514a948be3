//! The design surface as heights over the XY plane, for the z comparisons of the
//! sectioning gouge check (thesis 000 §7.2: "the x and y values of the contact points
//! on the comparison sections are substituted in the surface equation and then gouging
//! is checked based on the difference of the z values").
//!
//! The heights are the part's upper envelope from the one height-field query of the
//! geometry kernel ([`swarf_geom::height`]: Newton on `S_xy(u, v) = (x, y)` to 1e-10
//! mm, seeded from sample triangles), the same query the dexel verifier fills its
//! design grid with, so sectioning and verification agree at patch edges. This file
//! adds the patch edges as points, for the boundary test of the gouge check.
//!
//! The comparison is along z, as in the thesis and in the Z-map verifier; it assumes a
//! design that is a height field over XY.

use crate::error::FiveAxisError;
use swarf_geom::height::PartHeights;
use swarf_geom::{Part, Patch, Point3};

/// Points per patch edge in [`DesignSurface::boundary`].
const EDGE_SAMPLES: usize = 800;

/// The design surface of a part as heights over XY.
#[derive(Debug, Clone)]
pub struct DesignSurface {
    heights: PartHeights,
    patches: Vec<Patch>,
    boundary: Vec<Point3>,
}

impl DesignSurface {
    /// Prepares the part's patches for height queries.
    ///
    /// # Errors
    /// [`FiveAxisError::InvalidParameter`] (field `part`) for a patch the kernel
    /// cannot put in power form (it can any valid patch).
    pub fn new(part: &Part) -> Result<DesignSurface, FiveAxisError> {
        let heights = PartHeights::new(part)
            .map_err(|e| FiveAxisError::parameter("part", format!("{}: {e}", part.name)))?;
        Ok(DesignSurface {
            heights,
            patches: part.patches.clone(),
            boundary: part.patches.iter().flat_map(edge_points).collect(),
        })
    }

    /// Points along every patch edge (`EDGE_SAMPLES` per edge): where section planes
    /// pass a thin corner of the design's XY shadow without a sample in it, the
    /// gouge check tests these directly.
    pub fn boundary(&self) -> &[Point3] {
        &self.boundary
    }

    /// The design height at `(x, y)`: the highest patch point above it, with the patch
    /// index; `None` outside every patch's XY shadow.
    ///
    /// # Units
    /// mm.
    pub fn height(&self, x: f64, y: f64) -> Option<(f64, usize)> {
        self.locate(x, y).map(|l| (l.z, l.patch))
    }

    /// The highest patch point above `(x, y)` with its patch and parameters; `None`
    /// outside every patch's XY shadow.
    pub fn locate(&self, x: f64, y: f64) -> Option<Located> {
        self.heights.at(x, y).map(|h| Located {
            z: h.z,
            patch: h.patch,
            u: h.uv[0],
            v: h.uv[1],
        })
    }

    /// The patches, in part order.
    pub fn patch(&self, k: usize) -> Option<&Patch> {
        self.patches.get(k)
    }
}

/// A design point found above an XY position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Located {
    /// Height, mm.
    pub z: f64,
    /// Patch index.
    pub patch: usize,
    /// Parameter u.
    pub u: f64,
    /// Parameter v.
    pub v: f64,
}

fn edge_points(patch: &Patch) -> Vec<Point3> {
    let [[u0, u1], [v0, v1]] = patch.domain();
    let mut out = Vec::with_capacity(4 * EDGE_SAMPLES);
    for k in 0..EDGE_SAMPLES {
        let t = k as f64 / (EDGE_SAMPLES - 1) as f64;
        let (u, v) = (u0 + (u1 - u0) * t, v0 + (v1 - v0) * t);
        out.extend([
            patch.eval(u, v0),
            patch.eval(u, v1),
            patch.eval(u0, v),
            patch.eval(u1, v),
        ]);
    }
    out
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// The die of thesis 000 eq. 6.1 (`parts/die.toml`).
    pub(crate) fn die() -> Part {
        let pts = [
            [-99.4, 0.0, 12.1],
            [-54.95, 0.0, 24.6],
            [-4.9, 0.0, 43.8],
            [-99.4, -65.65, -13.3],
            [-54.95, -65.65, -7.625],
            [-4.9, -65.65, 2.8],
            [-99.4, -103.2, 37.5],
            [-54.95, -103.2, 39.3],
            [-4.9, -103.2, 49.8],
        ];
        let points = pts.iter().map(|p| Point3::new(p[0], p[1], p[2])).collect();
        Part::new("die", vec![Patch::bezier([2, 2], points).unwrap()])
    }

    /// Eq. 6.1 in closed form.
    pub(crate) fn die_closed_form(u: f64, v: f64) -> [f64; 3] {
        let x = -99.4 + 88.9 * v + 5.6 * v * v;
        let y = -131.3 * u + 28.1 * u * u;
        let z = 5.9 * (u * u * v * v + u * u * v) - 3.9 * v * v * u + 76.2 * u * u + 6.7 * v * v
            - 27.3 * u * v
            - 50.8 * u
            + 25.0 * v
            + 12.1;
        [x, y, z]
    }

    #[test]
    fn die_heights_match_the_closed_form() {
        let d = DesignSurface::new(&die()).unwrap();
        for i in 0..=20 {
            for j in 0..=20 {
                let (u, v) = (i as f64 / 20.0, j as f64 / 20.0);
                let [x, y, z] = die_closed_form(u, v);
                let (h, k) = d.height(x, y).unwrap();
                assert_eq!(k, 0);
                assert!((h - z).abs() < 1e-9, "({u}, {v}): {h} vs {z}");
            }
        }
        assert!(d.height(10.0, -50.0).is_none());
        assert!(d.height(-50.0, 5.0).is_none());
        assert!(d.height(f64::NAN, 0.0).is_none());
    }

    #[test]
    fn upper_envelope_of_two_patches() {
        let flat = |z: f64| {
            Patch::bezier(
                [1, 1],
                vec![
                    Point3::new(0.0, 0.0, z),
                    Point3::new(0.0, 10.0, z),
                    Point3::new(10.0, 0.0, z),
                    Point3::new(10.0, 10.0, z),
                ],
            )
            .unwrap()
        };
        let part = Part::new("two", vec![flat(1.0), flat(2.0)]);
        assert_eq!(
            DesignSurface::new(&part).unwrap().height(3.0, 4.0),
            Some((2.0, 1))
        );
    }
}
