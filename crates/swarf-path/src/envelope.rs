//! The part's upper envelope: which CC points a 3-axis tool can reach.
//!
//! For 3-axis work the material of a part of several patches is everything below the
//! upper envelope of its patches seen along `+z` (`parts/README.md`). Patches may run
//! past their common edges and under each other (edge-convex.toml), so a CC point on
//! one patch may lie under another; a pass must not follow it there. A CC point is
//! *hidden* when the envelope at its `(x, y)` is above it by more than a margin; the
//! envelope height is read from a tessellation of the whole part (within `e` of it)
//! through the height-field query of swarf-geom ([`MeshHeights::upper`]): the highest
//! triangle over the point. With a margin at least
//! `e`, a point on the envelope is never hidden; points of two patches that cross
//! within the margin are both kept (the gouge check then settles the crease).

use swarf_geom::height::MeshHeights;
use swarf_geom::{Point3, TriMesh};

/// The upper envelope of a tessellated part.
#[derive(Debug, Clone)]
pub struct Envelope {
    surface: MeshHeights<'static>,
    margin: f64,
}

impl Envelope {
    /// The envelope of `mesh`; points more than `margin` (mm) below it are hidden.
    pub fn new(mesh: TriMesh, margin: f64) -> Envelope {
        Envelope {
            surface: MeshHeights::owned(mesh),
            margin,
        }
    }

    /// Height of the envelope at `(x, y)`, mm; `None` outside the part's outline.
    pub fn height(&self, x: f64, y: f64) -> Option<f64> {
        self.surface.upper(x, y)
    }

    /// True when the envelope at `p`'s `(x, y)` is above `p` by more than the margin.
    pub fn hides(&self, p: &Point3) -> bool {
        self.height(p.x, p.y).is_some_and(|z| z > p.z + self.margin)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_geom::height::vertical_hit as height_over;

    #[test]
    fn highest_triangle_wins_and_hidden_points_are_found() {
        let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
        let low = [p(0.0, 0.0, 0.0), p(10.0, 0.0, 0.0), p(0.0, 10.0, 0.0)];
        let high = [p(0.0, 0.0, 1.0), p(10.0, 0.0, 3.0), p(0.0, 10.0, 1.0)];
        let env = Envelope::new(TriMesh::from_triangles(&[low, high]), 0.01);
        let z = env.height(5.0, 2.0).unwrap();
        assert!((z - 2.0).abs() < 1e-12, "{z}");
        assert!(env.height(8.0, 8.0).is_none());
        assert!(env.hides(&p(5.0, 2.0, 0.0)));
        assert!(!env.hides(&p(5.0, 2.0, 1.995)));
        assert!(!env.hides(&p(20.0, 2.0, -50.0)));
        // Edge-on triangles are skipped, corners are inside.
        let wall = [p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0), p(0.5, 0.0, 9.0)];
        assert!(height_over(&wall, 0.5, 0.0).is_none());
        assert_eq!(height_over(&high, 10.0, 0.0), Some(3.0));
    }
}
