//! The design surface as heights over the XY plane, for the z comparisons of the
//! sectioning gouge check (thesis 000 §7.2: "the x and y values of the contact points
//! on the comparison sections are substituted in the surface equation and then gouging
//! is checked based on the difference of the z values").
//!
//! For a patch `S(u, v)` and a query `(x, y)`, Newton's method solves
//! `S_xy(u, v) = (x, y)` with the 2x2 Jacobian `[S_u.xy, S_v.xy]`, parameters clamped
//! into the domain. It starts from the `(u, v)` of the nearest node of a sample grid,
//! found through a lookup table over the patch's XY box (each table cell holds the grid
//! node nearest its centre). A query whose clamped answer misses `(x, y)` by more than
//! [`XY_MATCH`] lies outside the patch's XY shadow. With several patches the height is
//! the highest (the part's upper envelope, `../shared/parts/README.md`).
//!
//! The comparison is along z, as in the thesis and in the Z-map verifier; it assumes a
//! design that is a height field over XY (where a patch folds over itself in XY, the
//! Newton root nearest the start is taken).

use swarf_geom::{Part, Patch};

/// A query counts as on the patch when the clamped Newton answer is within this of
/// `(x, y)` (mm).
pub const XY_MATCH: f64 = 1e-7;
/// Newton steps on the XY equations.
const NEWTON_STEPS: usize = 12;
/// Nodes of the sample grid per direction and per knot span.
const NODES_PER_SPAN: usize = 16;
/// Cells of the start lookup table per direction.
const LOOKUP: usize = 64;

/// One patch with its start lookup table.
#[derive(Debug, Clone)]
struct Indexed {
    patch: Patch,
    min: [f64; 2],
    cell: [f64; 2],
    starts: Vec<[f64; 2]>,
}

/// Points per patch edge in [`DesignSurface::boundary`].
const EDGE_SAMPLES: usize = 800;

/// The design surface of a part as heights over XY.
#[derive(Debug, Clone)]
pub struct DesignSurface {
    patches: Vec<Indexed>,
    boundary: Vec<swarf_geom::Point3>,
}

impl DesignSurface {
    /// Prepares the part's patches for height queries.
    pub fn new(part: &Part) -> DesignSurface {
        DesignSurface {
            patches: part.patches.iter().map(index_patch).collect(),
            boundary: part.patches.iter().flat_map(edge_points).collect(),
        }
    }

    /// Points along every patch edge (`EDGE_SAMPLES` per edge): where section planes
    /// pass a thin corner of the design's XY shadow without a sample in it, the
    /// gouge check tests these directly.
    pub fn boundary(&self) -> &[swarf_geom::Point3] {
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
        let mut best: Option<Located> = None;
        for (k, ip) in self.patches.iter().enumerate() {
            if let Some((z, [u, v])) = ip.height(x, y)
                && best.is_none_or(|b| z > b.z)
            {
                best = Some(Located { z, patch: k, u, v });
            }
        }
        best
    }

    /// The patches, in part order.
    pub fn patch(&self, k: usize) -> Option<&Patch> {
        self.patches.get(k).map(|ip| &ip.patch)
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

impl Indexed {
    fn height(&self, x: f64, y: f64) -> Option<(f64, [f64; 2])> {
        let i = ((x - self.min[0]) / self.cell[0]).floor();
        let j = ((y - self.min[1]) / self.cell[1]).floor();
        let n = LOOKUP as f64;
        if !(i >= -1.0 && i <= n && j >= -1.0 && j <= n) {
            return None;
        }
        let (i, j) = (
            i.clamp(0.0, n - 1.0) as usize,
            j.clamp(0.0, n - 1.0) as usize,
        );
        let [mut u, mut v] = self.starts[i * LOOKUP + j];
        let mut z = f64::NAN;
        let mut miss = f64::INFINITY;
        for _ in 0..NEWTON_STEPS {
            let d = self.patch.derivs(u, v);
            let (rx, ry) = (x - d.point.x, y - d.point.y);
            z = d.point.z;
            miss = (rx * rx + ry * ry).sqrt();
            if miss <= XY_MATCH * 1e-3 {
                break;
            }
            let det = d.du.x * d.dv.y - d.du.y * d.dv.x;
            if det.abs() < 1e-300 || !det.is_finite() {
                return None;
            }
            let du = (rx * d.dv.y - ry * d.dv.x) / det;
            let dv = (d.du.x * ry - d.du.y * rx) / det;
            (u, v) = self.patch.clamp_params(u + du, v + dv);
        }
        if miss > XY_MATCH {
            let p = self.patch.eval(u, v);
            z = p.z;
            miss = (x - p.x).hypot(y - p.y);
        }
        (miss <= XY_MATCH && z.is_finite()).then_some((z, [u, v]))
    }
}

fn edge_points(patch: &Patch) -> Vec<swarf_geom::Point3> {
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

fn index_patch(patch: &Patch) -> Indexed {
    let [[u0, u1], [v0, v1]] = patch.domain();
    let [pu, pv] = patch.degree();
    let nu = NODES_PER_SPAN * (patch.count()[0] - pu).max(1) + 1;
    let nv = NODES_PER_SPAN * (patch.count()[1] - pv).max(1) + 1;
    let mut nodes = Vec::with_capacity(nu * nv);
    let (mut min, mut max) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for i in 0..nu {
        for j in 0..nv {
            let u = u0 + (u1 - u0) * i as f64 / (nu - 1) as f64;
            let v = v0 + (v1 - v0) * j as f64 / (nv - 1) as f64;
            let p = patch.eval(u, v);
            for k in 0..2 {
                min[k] = min[k].min(p[k]);
                max[k] = max[k].max(p[k]);
            }
            nodes.push(([p.x, p.y], [u, v]));
        }
    }
    let cell = [0, 1].map(|k| ((max[k] - min[k]) / LOOKUP as f64).max(1e-9));
    let mut starts = vec![[u0, v0]; LOOKUP * LOOKUP];
    for (slot, start) in starts.iter_mut().enumerate() {
        let c = [
            min[0] + cell[0] * ((slot / LOOKUP) as f64 + 0.5),
            min[1] + cell[1] * ((slot % LOOKUP) as f64 + 0.5),
        ];
        let nearest = nodes.iter().min_by(|a, b| {
            let da = (a.0[0] - c[0]).hypot(a.0[1] - c[1]);
            let db = (b.0[0] - c[0]).hypot(b.0[1] - c[1]);
            da.total_cmp(&db)
        });
        if let Some(n) = nearest {
            *start = n.1;
        }
    }
    Indexed {
        patch: patch.clone(),
        min,
        cell,
        starts,
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use swarf_geom::Point3;

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
        Part {
            name: "die".into(),
            patches: vec![Patch::bezier([2, 2], points).unwrap()],
        }
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
        let d = DesignSurface::new(&die());
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
        let part = Part {
            name: "two".into(),
            patches: vec![flat(1.0), flat(2.0)],
        };
        assert_eq!(DesignSurface::new(&part).height(3.0, 4.0), Some((2.0, 1)));
    }
}
