//! Faces: entity 144 (trimmed surface, IGES 5.3 sec. 4.34) as a patch and its
//! [`Trim`], each loop a 142 (curve on a parametric surface, sec. 4.32) sampled in
//! the surface's `(u, v)` (module doc of [`super`] for the tolerances), and a bare
//! independent 128 as a whole patch.

use super::curve::Join;
use super::params::Tok;
use super::{FaceOut, Iges, Problem};
use swarf_geom::trim::Trim;
use swarf_geom::{Face, Patch, Point3};

/// A trimming loop in a patch's `(u, v)`.
type Loop = Vec<[f64; 2]>;

/// Largest gap closed between the pieces of a loop and between its ends, and
/// largest distance of a model-space trimming point from its surface, mm, unless the
/// file's resolution (Global field 19) is coarser (IGES writers print 9 to 15
/// significant digits).
const GAP_MM: f64 = 1e-3;
/// Largest gap closed whatever the file's resolution, mm.
const MAX_GAP_MM: f64 = 0.1;
/// Samples per direction of the grid bounding `|S_u| + |S_v|`.
const SPEED_GRID: usize = 16;

impl Iges<'_> {
    /// An independent 128: its patch, trimmed to its declared `[U0, U1] x [V0, V1]`
    /// when that is smaller than the knot domain.
    pub(crate) fn bare_surface(&self, de: usize) -> Result<FaceOut, Problem> {
        let patch = self.nurbs_surface(de)?;
        let trim = match self.declared_range(de, &patch) {
            Some(r) => Some(
                Trim::new(vec![r]).map_err(|e| self.err(de, format!("parameter range: {e}")))?,
            ),
            None => None,
        };
        let name = self.name(de, None);
        Ok((
            patch,
            Face {
                name,
                surface: self.origin(de),
                trim,
            },
        ))
    }

    /// A 144: the patch of its surface and its trimming loops.
    pub(crate) fn trimmed_surface(&self, de: usize) -> Result<FaceOut, Problem> {
        let p = self.params(de, "trimmed surface")?;
        let sptr = p.ptr(self, 1)?;
        let n1 = p.int(self, 2)?;
        let n2 = p.count(self, 3, p.toks.len())?;
        let mut curves = Vec::with_capacity(n2 + 1);
        if n1 != 0 {
            curves.push(p.ptr(self, 4)?);
        }
        for k in 0..n2 {
            curves.push(p.ptr(self, 5 + k)?);
        }
        let (patch, mut loops) = self.surface_loops(&p, sptr, n1 != 0, &curves)?;
        if n1 == 0 {
            let [u, v] = patch.domain();
            let whole = vec![[u[0], v[0]], [u[1], v[0]], [u[1], v[1]], [u[0], v[1]]];
            let range = (self.entry(sptr, "surface")?.ty == 128)
                .then(|| self.declared_range(sptr, &patch))
                .flatten();
            if loops.is_empty() && range.is_none() {
                let name = self.name(de, Some(sptr));
                return Ok((
                    patch,
                    Face {
                        name,
                        surface: self.origin(sptr),
                        trim: None,
                    },
                ));
            }
            loops.insert(0, range.unwrap_or(whole));
            curves.insert(0, 0);
        }
        let trim = Trim::new(loops).map_err(|e| {
            let which: Vec<String> = curves
                .iter()
                .enumerate()
                .map(|(k, c)| {
                    if *c == 0 {
                        format!("loop[{k}] = the surface's parameter range")
                    } else {
                        format!("loop[{k}] = DE {c}")
                    }
                })
                .collect();
            self.err(de, format!("trimming loops ({}): {e}", which.join(", ")))
        })?;
        Ok((
            patch,
            Face {
                name: self.name(de, Some(sptr)),
                surface: self.origin(sptr),
                trim: Some(trim),
            },
        ))
    }

    /// The patch of surface `sptr` (a 128, or a 108 bounded by `curves[0]` when
    /// `bounded`) and the 142 loops `curves` in its `(u, v)`.
    fn surface_loops(
        &self,
        p: &super::Params,
        sptr: usize,
        bounded: bool,
        curves: &[usize],
    ) -> Result<(Patch, Vec<Loop>), Problem> {
        let de = p.de;
        let ty = self
            .entry(sptr, &format!("DE {de} parameter 1 (surface)"))?
            .ty;
        Ok(match ty {
            128 => {
                let patch = self.nurbs_surface(sptr)?;
                let loops = curves
                    .iter()
                    .map(|c| self.loop_uv(*c, sptr, &patch))
                    .collect::<Result<Vec<_>, _>>()?;
                (patch, loops)
            }
            108 if bounded => {
                let model = curves
                    .iter()
                    .map(|c| self.loop_model(*c, sptr))
                    .collect::<Result<Vec<_>, _>>()?;
                let plane = self.params(sptr, "plane")?;
                let patch = self.plane_patch(&plane, &model[0])?;
                let loops = curves
                    .iter()
                    .zip(&model)
                    .map(|(c, m)| self.project_loop(*c, m, &patch))
                    .collect::<Result<Vec<_>, _>>()?;
                (patch, loops)
            }
            108 => return Err(p.unsupported("an unbounded plane (108) as the outer boundary")),
            t => {
                return Err(p.unsupported(format!(
                    "surface DE {sptr} of type {t} (expected 128 or a bounded 108)"
                )));
            }
        })
    }

    /// The 142 at `c`, checked to lie on surface `sptr`: (BPTR, CPTR).
    fn curve_on_surface(&self, c: usize, sptr: usize) -> Result<(usize, usize), Problem> {
        let p = self.params(c, "curve on surface")?;
        if p.ty != 142 {
            return Err(p.unsupported(format!("trimming loop of type {} (expected 142)", p.ty)));
        }
        let s = p.ptr(self, 2)?;
        if s != sptr {
            return Err(self
                .err(
                    c,
                    format!(
                        "parameter 2: surface DE {s}; expected the trimmed surface's DE {sptr}"
                    ),
                )
                .into());
        }
        Ok((p.ptr(self, 3)?, p.ptr(self, 4)?))
    }

    /// Loop `c` in `(u, v)` of the 128 `patch`: its parameter-space curve, or its
    /// model-space curve projected.
    fn loop_uv(&self, c: usize, sptr: usize, patch: &Patch) -> Result<Vec<[f64; 2]>, Problem> {
        let (b, m) = self.curve_on_surface(c, sptr)?;
        if b == 0 {
            let model = self.loop_model(c, sptr)?;
            return self.project_loop(c, &model, patch);
        }
        let speed = speed_bound(patch);
        let tol = self.opts.trim_chord / speed;
        let gap = self.gap_mm() / speed;
        // A closed surface: a seam edge's curve may lie a period away (shift the
        // piece) or a degenerate edge may be left out (bridge the gap); try bridging
        // first, then shifting, and keep the first loop that does not cross itself.
        let period = periods(patch, self.gap_mm());
        let mut first = None;
        let tries: &[[f64; 2]] = if period == [0.0; 2] {
            &[[0.0; 2]]
        } else {
            &[[0.0; 2], period]
        };
        for &period in tries {
            let join = Join {
                gap,
                period,
                surface: Some((patch, self.gap_mm())),
            };
            let pts = match self.sample_curve(b, tol, join, &mut Vec::new()) {
                Err(Problem::Unsupported { .. }) if m != 0 => {
                    let model = self.loop_model(c, sptr)?;
                    return self.project_loop(c, &model, patch);
                }
                other => other,
            };
            let uv = pts.and_then(|pts| {
                let uv: Vec<[f64; 2]> = pts.iter().map(|q| [q.x, q.y]).collect();
                self.closed(c, uv, gap, patch)
            });
            if tries.len() == 1
                || uv
                    .as_ref()
                    .is_ok_and(|l| Trim::new(vec![l.clone()]).is_ok())
            {
                return uv;
            }
            if let Some(bridged) = first {
                return bridged;
            }
            first = Some(uv);
        }
        first.unwrap_or_else(|| Err(self.err(c, "no trimming loop").into()))
    }

    /// Loop `c`'s model-space curve in mm.
    fn loop_model(&self, c: usize, sptr: usize) -> Result<Vec<Point3>, Problem> {
        let (_, m) = self.curve_on_surface(c, sptr)?;
        if m == 0 {
            return Err(self
                .err(
                    c,
                    "parameter 4: no model-space curve, and no parameter-space curve swarf can use",
                )
                .into());
        }
        let s = self.rec.mm_per_unit;
        let pts = self.sample_curve(
            m,
            self.opts.trim_chord / s,
            Join {
                gap: self.gap_mm() / s,
                period: [0.0; 2],
                surface: None,
            },
            &mut Vec::new(),
        )?;
        Ok(pts.into_iter().map(|q| q * s).collect())
    }

    /// Model-space loop points (mm) projected on `patch`, each from the previous.
    fn project_loop(
        &self,
        c: usize,
        model: &[Point3],
        patch: &Patch,
    ) -> Result<Vec<[f64; 2]>, Problem> {
        let mut uv: Vec<[f64; 2]> = Vec::with_capacity(model.len());
        for (k, q) in model.iter().enumerate() {
            let pr = match uv.last() {
                None => patch.project(q),
                Some(&[u, v]) => patch.project_from(q, u, v),
            };
            let off = self.gap_mm();
            if pr.distance.is_nan() || pr.distance > off {
                return Err(self.err(c, format!(
                    "model-space point {k} ({:.6}, {:.6}, {:.6}) mm lies {:.3e} mm from the surface; expected within {off:.1e}",
                    q.x, q.y, q.z, pr.distance
                )).into());
            }
            uv.push([pr.u, pr.v]);
        }
        let speed = speed_bound(patch);
        self.closed(c, uv, self.gap_mm() / speed, patch)
    }

    /// `uv` as a closed loop (last point dropped when it meets the first within `gap`).
    /// When the ends differ in `(u, v)` but are the same point of `patch` (a
    /// degenerate closing edge left out), the loop closes with the straight `(u, v)`
    /// segment between them.
    fn closed(
        &self,
        c: usize,
        mut uv: Vec<[f64; 2]>,
        gap: f64,
        patch: &Patch,
    ) -> Result<Vec<[f64; 2]>, Problem> {
        let (Some(&a), Some(&b)) = (uv.first(), uv.last()) else {
            return Err(self.err(c, "empty trimming loop").into());
        };
        let d = (a[0] - b[0]).hypot(a[1] - b[1]);
        let d3 = (patch.eval(a[0], a[1]) - patch.eval(b[0], b[1])).norm();
        if d > gap && d3 <= self.gap_mm() && uv.len() >= 3 {
            return Ok(uv);
        }
        if d.is_nan() || d > gap || uv.len() < 3 {
            return Err(self.err(c, format!(
                "open trimming loop: its end is {d:.3e} (u, v) from its start; expected a closed loop (gap <= {gap:.1e})"
            )).into());
        }
        uv.pop();
        Ok(uv)
    }

    /// The gap closed in loops and allowed off the surface, mm: [`GAP_MM`] or the
    /// file's resolution, whichever is larger, at most [`MAX_GAP_MM`].
    fn gap_mm(&self) -> f64 {
        GAP_MM.max(self.rec.resolution_mm.min(MAX_GAP_MM))
    }

    /// Where a face's surface comes from: `DE 5 type 128 (rational B-spline
    /// surface)`.
    fn origin(&self, de: usize) -> Option<String> {
        let ty = self.rec.entries.get(de / 2)?.ty;
        let what = match ty {
            128 => "rational B-spline surface",
            108 => "plane",
            _ => "surface",
        };
        Some(format!("DE {de} type {ty} ({what})"))
    }

    /// A face's name: a 406 form 15 name property of entity `de`, else its label,
    /// else the same of `other` (its surface).
    fn name(&self, de: usize, other: Option<usize>) -> Option<String> {
        let of = |d: usize| {
            let label = self.rec.entries.get(d / 2).and_then(|e| e.label.clone());
            self.property_name(d).or(label)
        };
        of(de).or_else(|| other.and_then(of))
    }

    /// The name in a 406 form 15 among the property pointers that follow the
    /// parameters of a 144 or 128 (sec. 2.2.4.5.2: a count of back pointers, them, a
    /// count of property pointers, them). Names are optional: anything amiss gives
    /// `None`.
    fn property_name(&self, de: usize) -> Option<String> {
        let p = self.params(de, "name").ok()?;
        let len = p.toks.len();
        let after = match p.ty {
            144 => 5 + p.count(self, 3, len).ok()?,
            128 => {
                let c = |k| p.count(self, k, len).ok();
                let (k1, k2, m1, m2) = (c(1)?, c(2)?, c(3)?, c(4)?);
                14 + (k1 + m1 + 2) + (k2 + m2 + 2) + 4 * (k1 + 1) * (k2 + 1)
            }
            _ => return None,
        };
        let nb = p.count(self, after, len).ok()?;
        let at = after + 1 + nb;
        let np = p.count(self, at, len).ok()?;
        (0..np).find_map(|k| {
            let d = p.ptr(self, at + 1 + k).ok()?;
            let e = self.rec.entries.get(d / 2)?;
            if e.ty != 406 || e.form != 15 {
                return None;
            }
            match self.params(d, "name").ok()?.toks.get(2)? {
                Tok::Str(s) if !s.trim().is_empty() => Some(s.trim().to_string()),
                _ => None,
            }
        })
    }
}

/// The `(u, v)` periods of the patch: the domain's width in a direction where the
/// patch is closed (opposite edges within `gap` mm at a few samples), else 0.
fn periods(patch: &Patch, gap: f64) -> [f64; 2] {
    let [u, v] = patch.domain();
    let samples =
        |f: &dyn Fn(f64) -> f64| (0..=SPEED_GRID).all(|k| f(k as f64 / SPEED_GRID as f64) <= gap);
    let closed_u = samples(&|t| {
        let vv = v[0] + t * (v[1] - v[0]);
        (patch.eval(u[0], vv) - patch.eval(u[1], vv)).norm()
    });
    let closed_v = samples(&|t| {
        let uu = u[0] + t * (u[1] - u[0]);
        (patch.eval(uu, v[0]) - patch.eval(uu, v[1])).norm()
    });
    [
        if closed_u { u[1] - u[0] } else { 0.0 },
        if closed_v { v[1] - v[0] } else { 0.0 },
    ]
}

/// An upper bound (sampled, times 2) of `|S_u| + |S_v|` over the patch, mm per
/// parameter unit, at least 1e-12.
fn speed_bound(patch: &Patch) -> f64 {
    let [u, v] = patch.domain();
    let mut best: f64 = 1e-12;
    for a in 0..=SPEED_GRID {
        for b in 0..=SPEED_GRID {
            let s = u[0] + (u[1] - u[0]) * a as f64 / SPEED_GRID as f64;
            let t = v[0] + (v[1] - v[0]) * b as f64 / SPEED_GRID as f64;
            let d = patch.derivs(s, t);
            best = best.max(d.du.norm() + d.dv.norm());
        }
    }
    2.0 * best
}
