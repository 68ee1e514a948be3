//! Trimming curves sampled into polylines (IGES 5.3 sec. 4.3, 4.5, 4.13, 4.23):
//! 110 line (its two ends), 100 circular arc (centre, start, end, counter-clockwise
//! in the plane `z = ZT`; steps of `2 acos(1 - tol / r)` keep the sagitta within
//! `tol`), 126 rational B-spline curve (knots possibly unclamped, sampled by
//! [`NurbsCurve::polyline`] on `[V0, V1]`) and 102 composite curve (its pieces in
//! order, each end within `gap` of the next start). Each is mapped by its 124.

use super::{Iges, MAX_DEPTH, Params, Problem, VISITS_PER_ENTRY};
use std::f64::consts::TAU;
use swarf_geom::curve::MAX_POLYLINE_POINTS;
use swarf_geom::{NurbsCurve, Point3};

impl Iges<'_> {
    /// Points along curve `de` within `tol` (in the curve's space: file units, or
    /// parameter units of a surface), pieces of a composite joined within `gap`.
    ///
    /// # Errors
    /// An unsupported curve type, bad parameters, a composite whose pieces do not
    /// join or that contains itself (`path`: the composites being sampled), nesting
    /// deeper than [`MAX_DEPTH`], or far more curve visits than entities.
    pub(crate) fn sample_curve(
        &self,
        de: usize,
        tol: f64,
        join: Join<'_>,
        path: &mut Vec<usize>,
    ) -> Result<Vec<Point3>, Problem> {
        let visits = self.visits.get() + 1;
        self.visits.set(visits);
        if visits > VISITS_PER_ENTRY * (self.rec.entries.len() + 1) {
            return Err(self
                .err(de, "curves referenced far more often than the file has entities; expected each trimming curve used about once")
                .into());
        }
        let p = self.params(de, "curve")?;
        let pts = match p.ty {
            110 => {
                let v = p.reals(self, 1, 6)?;
                vec![Point3::new(v[0], v[1], v[2]), Point3::new(v[3], v[4], v[5])]
            }
            100 => {
                let v = p.reals(self, 1, 7)?;
                arc(v[0], [v[1], v[2]], [v[3], v[4]], [v[5], v[6]], tol)
                    .map_err(|m| self.err(de, m))?
            }
            126 => self.bspline_curve(&p, tol)?,
            102 => self.composite(&p, tol, join, path)?,
            t => {
                return Err(p.unsupported(format!(
                    "curve type {t} in a trimming loop (expected 100, 102, 110 or 126)"
                )));
            }
        };
        let map = self.transform_of(de)?;
        Ok(pts.iter().map(|q| map.apply(q)).collect())
    }

    /// A 102: its pieces in order, each starting within `join.gap` of the previous
    /// end (after a shift by whole periods on a closed surface).
    fn composite(
        &self,
        p: &Params,
        tol: f64,
        join: Join<'_>,
        path: &mut Vec<usize>,
    ) -> Result<Vec<Point3>, Problem> {
        let de = p.de;
        if path.len() >= MAX_DEPTH {
            return Err(self
                .err(
                    de,
                    format!("composite curves nested deeper than {MAX_DEPTH}"),
                )
                .into());
        }
        let n = p.count(self, 1, p.toks.len())?;
        let mut out: Vec<Point3> = Vec::new();
        path.push(de);
        for k in 0..n {
            let c = p.ptr(self, 2 + k)?;
            if path.contains(&c) {
                return Err(self
                    .err(
                        de,
                        format!(
                            "piece {} is DE {c}, which contains it: expected no cycle",
                            k + 1
                        ),
                    )
                    .into());
            }
            let mut piece = self.sample_curve(c, tol, join, path)?;
            if let (Some(&end), Some(&start)) = (out.last(), piece.first()) {
                let shift = join.shift(&end, &start);
                for q in &mut piece {
                    *q += shift;
                }
                let d = (end - (start + shift)).norm();
                let gap = join.gap;
                if d > gap && join.meet_on_surface(&end, &(start + shift)) {
                    out.extend(piece);
                    continue;
                }
                if d > gap {
                    return Err(self.err(de, format!(
                        "piece {} (DE {c}) starts {d:.3e} from the end of piece {k}; expected a connected curve (gap <= {gap:.1e})",
                        k + 1
                    )).into());
                }
                out.pop();
            }
            out.extend(piece);
        }
        path.pop();
        Ok(out)
    }

    /// A 126 sampled on `[V0, V1]`.
    fn bspline_curve(&self, p: &Params, tol: f64) -> Result<Vec<Point3>, Problem> {
        let size = p.toks.len();
        let k = p.count(self, 1, size)?;
        let m = p.count(self, 2, size)?;
        let n = k + 1;
        let nk = n + m + 1;
        let at = 7;
        let knots = p.reals(self, at, nk)?;
        let w = p.reals(self, at + nk, n)?;
        let xyz = p.reals(self, at + nk + n, 3 * n)?;
        let t = p.reals(self, at + nk + 4 * n, 2)?;
        let points = xyz
            .chunks(3)
            .map(|c| Point3::new(c[0], c[1], c[2]))
            .collect();
        let rational = p.int(self, 5)? == 0;
        let curve = NurbsCurve::new(m, knots, points, rational.then_some(w))
            .map_err(|e| self.err(p.de, format!("rational B-spline curve: {e}")))?;
        curve
            .polyline(t[0], t[1], tol)
            .map(|v| v.into_iter().map(|(_, q)| q).collect())
            .map_err(|e| self.err(p.de, format!("sampling: {e}")).into())
    }
}

/// How the pieces of a composite curve must meet.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Join<'a> {
    /// Largest gap between a piece's end and the next piece's start.
    pub gap: f64,
    /// For a curve in a surface's `(u, v)`: the surface and the largest gap in mm
    /// between the surface points of a piece's end and the next start (a degenerate
    /// edge, such as a sphere's pole, is often left out: its ends differ in `(u, v)`
    /// but meet on the surface).
    pub surface: Option<(&'a swarf_geom::Patch, f64)>,
    /// The `(u, v)` periods of a closed surface (0: not closed; always 0 in model
    /// space): writers may give a seam edge's parameter curve on the other side of
    /// the seam, a whole period away.
    pub period: [f64; 2],
}

impl Join<'_> {
    /// Whether `a` and `b` (in `(u, v)`) are the same surface point within the
    /// surface gap.
    fn meet_on_surface(&self, a: &Point3, b: &Point3) -> bool {
        self.surface
            .is_some_and(|(p, gap)| (p.eval(a.x, a.y) - p.eval(b.x, b.y)).norm() <= gap)
    }

    /// The shift by whole periods (-1, 0 or 1 in each direction) that brings
    /// `start` nearest `end`.
    fn shift(&self, end: &Point3, start: &Point3) -> swarf_geom::Vec3 {
        let mut best = swarf_geom::Vec3::zeros();
        let mut best_d = (end - start).norm();
        for a in [-1.0, 0.0, 1.0] {
            for b in [-1.0, 0.0, 1.0] {
                let s = swarf_geom::Vec3::new(a * self.period[0], b * self.period[1], 0.0);
                let d = (end - (start + s)).norm();
                if d < best_d - self.gap {
                    (best, best_d) = (s, d);
                }
            }
        }
        best
    }
}

/// An arc in the plane `z = zt` about `c` from `s` to `e`, counter-clockwise (a full
/// circle when `s == e`), within sagitta `tol`.
fn arc(zt: f64, c: [f64; 2], s: [f64; 2], e: [f64; 2], tol: f64) -> Result<Vec<Point3>, String> {
    let r = (s[0] - c[0]).hypot(s[1] - c[1]);
    if !(r.is_finite() && r > 0.0) {
        return Err(format!("circular arc: radius {r}; expected finite and > 0"));
    }
    let a0 = (s[1] - c[1]).atan2(s[0] - c[0]);
    let a1 = (e[1] - c[1]).atan2(e[0] - c[0]);
    let mut sweep = (a1 - a0).rem_euclid(TAU);
    if sweep <= 1e-12 {
        sweep = TAU;
    }
    let step = 2.0 * (1.0 - (tol / r).min(1.0)).acos();
    let n = (sweep / step.max(1e-300)).ceil().max(2.0);
    if n > MAX_POLYLINE_POINTS as f64 {
        return Err(format!(
            "circular arc of radius {r:.3e}: more than {MAX_POLYLINE_POINTS} points needed for a chord of {tol:.1e}"
        ));
    }
    let n = n as usize;
    let mut out: Vec<Point3> = (0..=n)
        .map(|k| {
            let a = a0 + sweep * k as f64 / n as f64;
            Point3::new(c[0] + r * a.cos(), c[1] + r * a.sin(), zt)
        })
        .collect();
    if let Some(last) = out.last_mut() {
        *last = Point3::new(e[0], e[1], zt);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A seam piece a period away is shifted back; one a period plus a bit away
    /// is not (nothing within the gap).
    #[test]
    fn seam_shift() {
        let j = Join {
            gap: 1e-6,
            period: [TAU, 0.0],
            surface: None,
        };
        let end = Point3::new(TAU, 0.5, 0.0);
        assert_eq!(j.shift(&end, &Point3::new(0.0, 0.5, 0.0)).x, TAU);
        assert_eq!(j.shift(&end, &Point3::new(TAU, 0.5, 0.0)).x, 0.0);
        let none = Join {
            period: [0.0; 2],
            ..j
        };
        assert_eq!(none.shift(&end, &Point3::new(0.0, 0.5, 0.0)).x, 0.0);
    }

    /// Arcs keep their sagitta within the tolerance (closed form: the chord of an
    /// arc of radius r over angle a deviates r (1 - cos(a / 2))).
    #[test]
    fn arc_sagitta() {
        let pts = arc(1.0, [0.0, 0.0], [5.0, 0.0], [0.0, 5.0], 1e-3).unwrap();
        assert_eq!(pts.last().unwrap(), &Point3::new(0.0, 5.0, 1.0));
        for w in pts.windows(2) {
            let m = (w[0].coords + w[1].coords) / 2.0;
            let sag = 5.0 - m.x.hypot(m.y);
            assert!(sag <= 1e-3 + 1e-12 && sag > 0.0, "{sag}");
        }
        let full = arc(0.0, [1.0, 1.0], [2.0, 1.0], [2.0, 1.0], 0.01).unwrap();
        assert!(full.len() > 10 && (full[full.len() / 2].x - 0.0).abs() < 0.05);
        assert!(arc(0.0, [0.0, 0.0], [0.0, 0.0], [0.0, 0.0], 0.01).is_err());
    }
}
