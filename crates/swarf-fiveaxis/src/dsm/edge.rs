//! The common edge at a station (module doc of [`crate::dsm`]): the point where the
//! two faces' exact heights along the station's horizontal line are equal.

use super::{Dsm, ROOT_TOL};
use crate::error::FiveAxisError;
use swarf_geom::height::Height;
use swarf_geom::solve::illinois;
use swarf_geom::{Point3, Vec3};

/// Scan step along a station's line when looking for the crossing, mm.
pub const EDGE_SCAN: f64 = 0.25;

/// The common edge at one station.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Station {
    /// Position of the station plane along the edge's direction, mm.
    pub s: f64,
    /// The edge point, mm.
    pub edge: Point3,
    /// Unit horizontal direction of the reference line, toward face 1's side (where
    /// face 1 is the part's surface).
    pub across: Vec3,
    /// Unit tangent of the edge curve (from neighbouring stations), pointing along
    /// the edge's direction.
    pub tangent: Vec3,
}

impl Dsm {
    /// The point at offset `t` along the reference line of station `s`, in XY.
    fn line_xy(&self, s: f64, t: f64) -> [f64; 2] {
        let m = self.across_dir();
        [s * self.along.x + t * m.x, s * self.along.y + t * m.y]
    }

    /// The horizontal direction across the edge (`z x along`).
    fn across_dir(&self) -> Vec3 {
        Vec3::new(-self.along.y, self.along.x, 0.0)
    }

    /// Height of face `k` at `xy`, if the face covers it.
    pub(super) fn height(&self, k: usize, xy: [f64; 2]) -> Option<f64> {
        self.surface_at(k, xy).map(|h| h.z)
    }

    /// Face `k`'s exact height, upward normal and parameters at `xy`, if it covers
    /// it.
    pub fn surface_at(&self, k: usize, xy: [f64; 2]) -> Option<Height> {
        self.heights[k.min(1)].at(xy[0], xy[1])
    }

    /// The range of face `k`'s control box along the horizontal unit direction
    /// `dir` (`p . dir` over its XY corners), mm.
    pub fn span(&self, k: usize, dir: Vec3) -> [f64; 2] {
        let b = self.face(k).patch().control_box();
        let centre = 0.5 * ((b.min.x + b.max.x) * dir.x + (b.min.y + b.max.y) * dir.y);
        let half = 0.5 * ((b.max.x - b.min.x) * dir.x.abs() + (b.max.y - b.min.y) * dir.y.abs());
        [centre - half, centre + half]
    }

    /// The edge's crossing parameter `t` on station `s`'s line and the sign of
    /// `z1 - z0` past it (the first crossing from the line's start).
    fn crossing(&self, s: f64) -> Result<(f64, f64), FiveAxisError> {
        let m = self.across_dir();
        let (r0, r1) = (self.span(0, m), self.span(1, m));
        let (lo, hi) = (r0[0].max(r1[0]), r0[1].min(r1[1]));
        let diff = |t: f64| -> Option<f64> {
            let xy = self.line_xy(s, t);
            Some(self.height(1, xy)? - self.height(0, xy)?)
        };
        let steps = ((hi - lo) / EDGE_SCAN).ceil().clamp(1.0, 1e6) as usize;
        let mut prev: Option<(f64, f64)> = None;
        for i in 0..=steps {
            let t = lo + (hi - lo) * i as f64 / steps as f64;
            let Some(d) = diff(t) else {
                prev = None;
                continue;
            };
            if let Some((tp, dp)) = prev
                && (dp < 0.0) != (d < 0.0)
            {
                let f = |x: f64| diff(x).unwrap_or(f64::NAN);
                let [a, b] = illinois(f, tp, t, dp, d, ROOT_TOL, 200);
                let root = if a.1.abs() <= b.1.abs() { a.0 } else { b.0 };
                return Ok((root, if dp < 0.0 { 1.0 } else { -1.0 }));
            }
            prev = Some((t, d));
        }
        Err(FiveAxisError::parameter(
            "faces",
            format!(
                "station {s:.4}: the two faces do not cross on the reference line (no valley there: faces that meet at a ridge, or only abut, give the tool nothing to drop into)"
            ),
        ))
    }

    /// The common edge at station `s` (mm along the edge direction).
    ///
    /// # Errors
    /// [`FiveAxisError::InvalidParameter`] on `faces` where the faces do not cross on
    /// the station's line.
    pub fn station(&self, s: f64) -> Result<Station, FiveAxisError> {
        let point = |s: f64| -> Result<(Point3, f64), FiveAxisError> {
            let (t, sign) = self.crossing(s)?;
            let xy = self.line_xy(s, t);
            let z = self.height(0, xy).unwrap_or(f64::NAN);
            Ok((Point3::new(xy[0], xy[1], z), sign))
        };
        let (edge, sign) = point(s)?;
        let point = |s: f64| point(s).map(|p| p.0);
        let h = 1e-3;
        let tangent = match (point(s - h), point(s + h)) {
            (Ok(a), Ok(b)) => (b - a).normalize(),
            (Ok(a), Err(_)) => (edge - a).normalize(),
            (Err(_), Ok(b)) => (b - edge).normalize(),
            (Err(e), Err(_)) => return Err(e),
        };
        Ok(Station {
            s,
            edge,
            across: self.across_dir() * sign,
            tangent,
        })
    }

    /// The footprint at offset `w` from `station`'s edge toward face `1 - k` (the
    /// face the tool spins onto when dropped on face `k`), in XY.
    pub fn footprint(&self, station: &Station, k: usize, w: f64) -> [f64; 2] {
        let sign = if k == 0 { 1.0 } else { -1.0 };
        let m = station.across * sign * w;
        [station.edge.x + m.x, station.edge.y + m.y]
    }
}
