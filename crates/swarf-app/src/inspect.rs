//! `swarf inspect PART`: a summary of a part (patches, degrees, box, principal
//! curvatures) or of a mesh (counts, box, defects), as text or JSON.
//!
//! Per face, computed by the kernel:
//!
//! - the area inside its trimming loops, [`swarf_geom::Patch::area`] (Green's theorem,
//!   Gauss-Legendre: exact to rounding for the loops as read);
//! - the box is [`swarf_geom::Patch::surface_box`] to [`BOX_TOL`]: each face touches the surface
//!   (it is spanned by surface points) and the surface reaches at most [`BOX_TOL`]
//!   beyond it, found by Bezier subdivision;
//! - the principal curvature ranges are [`swarf_geom::Patch::curvature_range`] on a
//!   [`CURVATURE_SAMPLES`]-squared uniform parameter grid, corners and edges included:
//!   every reported extreme is attained at a grid point (the true range holds the
//!   reported one; an extreme between grid points is not caught).
//!
//! Patches are summarised in parallel and reported in file order. Every number written
//! is finite: a patch with no point that has a normal, or whose figures overflow, is
//! an error naming the patch; a mesh with no triangle corner of finite coordinates is
//! an error too (it has no box).

use crate::error::{Result, bail};
use crate::model::Model;
use rayon::prelude::*;
use serde::Serialize;
use swarf_geom::{Part, TriMesh};

/// Samples per direction for the curvature survey.
pub const CURVATURE_SAMPLES: usize = 101;
/// The reported box of a patch is within this of the surface's true box, mm.
pub const BOX_TOL: f64 = 1e-6;

/// Summary of one face: its patch, and from a CAD file its name, origin and trims
/// (lengths mm, areas mm², curvatures 1/mm).
#[derive(Debug, Serialize)]
pub struct PatchSummary {
    /// Patch index (what a job's `faces` selects).
    pub index: usize,
    /// The face's name in the CAD file.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// The file's entity for the surface (e.g. `#31 CYLINDRICAL_SURFACE`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub surface: Option<String>,
    /// Trimming loops (outer first) and their points, absent for a whole patch.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub trim: Option<TrimSummary>,
    /// Area of the face (inside its trims), mm².
    pub area: f64,
    /// Bezier, B-spline or NURBS.
    pub kind: String,
    /// Degrees in u and v.
    pub degree: [usize; 2],
    /// Control points in u and v.
    pub control_points: [usize; 2],
    /// Parameter domain.
    pub domain: [[f64; 2]; 2],
    /// Box corner, mm.
    pub bbox_min: [f64; 3],
    /// Box corner, mm.
    pub bbox_max: [f64; 3],
    /// Range of the first principal curvature, 1/mm.
    pub k1: [f64; 2],
    /// Range of the second principal curvature, 1/mm.
    pub k2: [f64; 2],
}

/// The trimming loops of a face, counted.
#[derive(Debug, Serialize)]
pub struct TrimSummary {
    /// Loops: one outer, the rest holes.
    pub loops: usize,
    /// Points of all loops.
    pub points: usize,
}

/// Summarises face `index` of `part`: its patch's box to [`BOX_TOL`], the ranges of
/// its principal curvatures over a parameter grid (module doc), its area inside its
/// trims, and what the file says of it.
///
/// # Errors
/// A patch with no normal at any grid point, or with a figure that is not finite.
pub fn summarise_patch(part: &Part, index: usize) -> Result<PatchSummary> {
    let patch = &part.patches[index];
    let trim = part.trim(index);
    let bbox = patch.surface_box(BOX_TOL)?.inner;
    let Some(k) = patch.curvature_range(CURVATURE_SAMPLES)? else {
        let n = CURVATURE_SAMPLES;
        bail!(
            "patch {index}: no point of the {n} x {n} parameter grid has a normal (du x dv \
             vanishes everywhere); expected a surface, not a curve or a point"
        );
    };
    let summary = PatchSummary {
        index,
        name: part.face_name(index).map(str::to_owned),
        surface: part.faces.get(index).and_then(|f| f.surface.clone()),
        trim: trim.map(|t| TrimSummary {
            loops: t.loops().len(),
            points: t.point_count(),
        }),
        area: patch.area(trim),
        kind: format!("{:?}", patch.kind()),
        degree: patch.degree(),
        control_points: patch.count(),
        domain: patch.domain(),
        bbox_min: bbox.min.coords.into(),
        bbox_max: bbox.max.coords.into(),
        k1: k.k1,
        k2: k.k2,
    };
    summary.check_finite()?;
    Ok(summary)
}

impl PatchSummary {
    /// Fails naming the patch and the first figure that is not finite.
    fn check_finite(&self) -> Result<()> {
        let [[u0, u1], [v0, v1]] = self.domain;
        let figures: [(&str, &[f64]); 6] = [
            ("domain", &[u0, u1, v0, v1]),
            ("bounding box", &self.bbox_min),
            ("bounding box", &self.bbox_max),
            ("k1", &self.k1),
            ("k2", &self.k2),
            ("area", &[self.area]),
        ];
        for (name, values) in figures {
            if let Some(x) = values.iter().find(|x| !x.is_finite()) {
                bail!(
                    "patch {}: {name} is {x}; expected finite numbers (control points too \
                     large for f64 arithmetic?)",
                    self.index
                );
            }
        }
        Ok(())
    }
}

/// The summaries of the faces of `part`, computed in parallel and returned in order;
/// the first error in face order.
///
/// # Errors
/// As [`summarise_patch`].
pub fn summarise_patches(part: &Part) -> Result<Vec<PatchSummary>> {
    let all: Vec<Result<PatchSummary>> = (0..part.patches.len())
        .into_par_iter()
        .map(|i| summarise_patch(part, i))
        .collect();
    all.into_iter().collect()
}

/// The summary of `model` as text, or as JSON when `json`.
///
/// # Errors
/// As [`summarise_patch`]; a mesh with no triangle corner of finite coordinates.
pub fn inspect(model: &Model, json: bool) -> Result<String> {
    match model {
        Model::Patches(part) => {
            let patches = summarise_patches(part)?;
            if json {
                let v = serde_json::json!({ "name": part.name, "patches": patches });
                Ok(serde_json::to_string_pretty(&v)? + "\n")
            } else {
                Ok(patch_text(&part.name, &patches))
            }
        }
        Model::Mesh { name, mesh } => mesh_text(name, mesh, json),
    }
}

fn fmt3(v: [f64; 3]) -> String {
    format!("({:.3}, {:.3}, {:.3})", v[0], v[1], v[2])
}

/// The text form of a part summary.
pub fn patch_text(name: &str, patches: &[PatchSummary]) -> String {
    let mut s = format!("part {name}: {} patch(es), units mm\n", patches.len());
    for p in patches {
        let name = p
            .name
            .as_ref()
            .map(|n| format!(" {n:?}"))
            .unwrap_or_default();
        let from = p
            .surface
            .as_ref()
            .map(|e| format!(" from {e}"))
            .unwrap_or_default();
        s += &format!(
            "  patch {}{name}{from}: {}, degree {}x{}, {}x{} control points, u in [{}, {}], v in [{}, {}]\n",
            p.index,
            p.kind,
            p.degree[0],
            p.degree[1],
            p.control_points[0],
            p.control_points[1],
            p.domain[0][0],
            p.domain[0][1],
            p.domain[1][0],
            p.domain[1][1]
        );
        match &p.trim {
            Some(t) => {
                s += &format!(
                    "    trimmed: {} loop(s) ({} hole(s)), {} points; area {:.6} mm²\n",
                    t.loops,
                    t.loops - 1,
                    t.points,
                    p.area
                )
            }
            None => s += &format!("    whole patch; area {:.6} mm²\n", p.area),
        }
        s += &format!(
            "    bounding box{} {} .. {} mm\n",
            if p.trim.is_some() {
                " of the untrimmed patch"
            } else {
                ""
            },
            fmt3(p.bbox_min),
            fmt3(p.bbox_max)
        );
        s += &format!(
            "    principal curvature k1 in [{:.6}, {:.6}], k2 in [{:.6}, {:.6}] 1/mm \
             (positive bends toward the normal du x dv)\n",
            p.k1[0], p.k1[1], p.k2[0], p.k2[1]
        );
    }
    s
}

fn mesh_text(name: &str, mesh: &TriMesh, json: bool) -> Result<String> {
    let bbox = mesh.aabb();
    if bbox.is_empty() {
        bail!(
            "mesh {name}: no triangle has a corner with finite coordinates ({} triangles); \
             expected finite x, y, z",
            mesh.triangles.len()
        );
    }
    let report = mesh.validate();
    if json {
        let v = serde_json::json!({
            "name": name,
            "triangles": mesh.triangles.len(),
            "vertices": mesh.vertices.len(),
            "bbox_min": <[f64; 3]>::from(bbox.min.coords),
            "bbox_max": <[f64; 3]>::from(bbox.max.coords),
            "non_finite": report.non_finite,
            "degenerate": report.degenerate,
            "duplicate": report.duplicate,
        });
        Ok(serde_json::to_string_pretty(&v)? + "\n")
    } else {
        let mut s = format!(
            "mesh {name}: {} triangles, {} vertices\n  bounding box {} .. {} mm\n",
            mesh.triangles.len(),
            mesh.vertices.len(),
            fmt3(bbox.min.coords.into()),
            fmt3(bbox.max.coords.into())
        );
        if report.is_clean() {
            s += "  no degenerate, non-finite or duplicate triangles\n";
        } else {
            s += &format!("{report}\n");
        }
        Ok(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_geom::{Face, Patch, Point3, Trim};

    /// `z = a x^2` over `[0, l] x [0, w]`: `x = l u`, `z = a l^2 u^2`, `y = w v`.
    fn parabolic(a: f64, l: f64, w: f64) -> Patch {
        let pts = [(0.0, 0.0), (0.5 * l, 0.0), (l, a * l * l)]
            .iter()
            .flat_map(|&(x, z)| [Point3::new(x, 0.0, z), Point3::new(x, w, z)])
            .collect();
        Patch::bezier([2, 1], pts).unwrap()
    }

    /// Four points on a line: a patch without a normal anywhere.
    fn line() -> Patch {
        let pts = (0..4).map(|k| Point3::new(k as f64, 0.0, 0.0)).collect();
        Patch::bezier([1, 1], pts).unwrap()
    }

    #[test]
    fn a_parabolic_cylinder_matches_its_closed_forms() {
        let (a, l, w) = (0.02, 30.0, 12.0);
        let part = Part::new("p", vec![parabolic(a, l, w); 5]);
        let s = summarise_patch(&part, 4).unwrap();
        // Arc length of z = a x^2 over [0, l], times the width.
        let arc = |x: f64| {
            let t = 2.0 * a * x;
            x / 2.0 * (1.0 + t * t).sqrt() + t.asinh() / (4.0 * a)
        };
        assert!((s.area - w * arc(l)).abs() < 1e-9 * s.area, "{}", s.area);
        assert_eq!((s.index, s.degree, s.control_points), (4, [2, 1], [3, 2]));
        for (k, want) in [l, w, a * l * l].iter().enumerate() {
            assert!(s.bbox_min[k].abs() <= BOX_TOL, "{:?}", s.bbox_min);
            assert!((s.bbox_max[k] - want).abs() <= BOX_TOL, "{:?}", s.bbox_max);
        }
        // curvature along x: 2a / (1 + (2 a x)^2)^1.5, largest at x = 0, least at x = l
        // (both grid points); across: 0. The normal du x dv points up (+z).
        let kx = |x: f64| 2.0 * a / (1.0 + (2.0 * a * x).powi(2)).powf(1.5);
        assert!((s.k1[0] - kx(l)).abs() < 1e-12 && (s.k1[1] - kx(0.0)).abs() < 1e-12);
        assert!(s.k2.iter().all(|k| k.abs() < 1e-12), "{:?}", s.k2);
        let text = patch_text("p", &[s]);
        assert!(text.contains("bounding box (0.000, 0.000, 0.000) .. (30.000, 12.000, 18.000) mm"));
    }

    #[test]
    fn the_first_bad_patch_in_order_is_named() {
        let mut patches = vec![parabolic(0.01, 5.0, 5.0); 40];
        patches[31] = line();
        patches[17] = line();
        let e = summarise_patches(&Part::new("p", patches.clone()))
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("patch 17: no point of the 101 x 101"), "{e}");
        let part = Part::new("p", patches[..17].to_vec());
        let text = inspect(&Model::Patches(part), false).unwrap();
        let order: Vec<usize> = text
            .lines()
            .filter_map(|l| l.trim().strip_prefix("patch "))
            .map(|l| l.split(':').next().unwrap().parse().unwrap())
            .collect();
        assert_eq!(order, (0..17).collect::<Vec<_>>());
    }

    #[test]
    fn a_cad_face_shows_its_name_origin_and_trims() {
        let mut part = Part::new("p", vec![parabolic(0.02, 30.0, 12.0)]);
        let square = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let hole = vec![[0.4, 0.4], [0.6, 0.4], [0.5, 0.6]];
        part.faces = vec![Face {
            name: Some("floor".into()),
            surface: Some("#12 B_SPLINE_SURFACE_WITH_KNOTS".into()),
            trim: Some(Trim::new(vec![square, hole]).unwrap()),
        }];
        let whole = part.patches[0].area(None);
        let text = inspect(&Model::Patches(part), false).unwrap();
        assert!(
            text.contains("patch 0 \"floor\" from #12 B_SPLINE_SURFACE_WITH_KNOTS: Bezier"),
            "{text}"
        );
        assert!(
            text.contains("trimmed: 2 loop(s) (1 hole(s)), 7 points; area "),
            "{text}"
        );
        let area: f64 = text
            .split("area ")
            .nth(1)
            .unwrap()
            .split(' ')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        assert!(area < whole && area > 0.9 * whole, "{area} of {whole}");
    }

    #[test]
    fn a_mesh_without_finite_corners_has_no_box() {
        let nan = Point3::new(f64::NAN, 0.0, f64::INFINITY);
        let mesh = TriMesh::from_triangles(&[[nan, nan, nan]]);
        let model = Model::Mesh {
            name: "m".into(),
            mesh,
        };
        let e = inspect(&model, true).unwrap_err().to_string();
        assert!(
            e.starts_with("mesh m: no triangle has a corner with finite"),
            "{e}"
        );
    }
}
