//! The one seeding scheme of the height query: every patch sampled on a uniform
//! parameter grid, the sample triangles indexed in XY, each carrying its corners'
//! `(u, v)`; a query point inside a sample triangle gets the interpolated `(u, v)`
//! there as its Newton start, and only the two highest patches over the point are
//! kept (derivation in [`super`]).

use crate::mesh::{TriMesh, XyIndex};
use crate::part::Part;
use crate::patch::Patch;
use crate::trim::Trim;

/// Target control-net length per sample of a patch, mm.
pub const SAMPLE_SPACING: f64 = 1.0;
/// Fewest samples per direction of a patch.
pub const MIN_SAMPLES: usize = 8;
/// Most samples per direction of a patch.
pub const MAX_SAMPLES: usize = 1024;

/// A Newton start on one patch: the sampled height and parameters there.
#[derive(Debug, Clone, Copy)]
pub(super) struct Guess {
    pub(super) z: f64,
    pub(super) uv: [f64; 2],
    pub(super) patch: u32,
}

/// No start (the slot of a patch not seen yet).
pub(super) const NO_GUESS: Guess = Guess {
    z: f64::NEG_INFINITY,
    uv: [0.0; 2],
    patch: u32::MAX,
};

/// The sample triangles of a part, with their parameters and patches.
#[derive(Debug, Clone)]
pub(super) struct Samples {
    pub(super) mesh: TriMesh,
    /// Per vertex `(u, v)`.
    uv: Vec<[f64; 2]>,
    /// Per triangle, its patch.
    patch_of: Vec<u32>,
    pub(super) index: XyIndex,
}

impl Samples {
    /// Samples every patch of `part` (module doc) and indexes the triangles.
    pub(super) fn new(part: &Part) -> Samples {
        let mut vertices = Vec::new();
        let mut uv = Vec::new();
        let mut triangles = Vec::new();
        let mut patch_of = Vec::new();
        for (pi, patch) in part.patches.iter().enumerate() {
            let [nu, nv] = sample_counts(patch);
            let [[u0, u1], [v0, v1]] = patch.domain();
            let base = vertices.len() as u32;
            for a in 0..=nu {
                for b in 0..=nv {
                    let u = u0 + (u1 - u0) * a as f64 / nu as f64;
                    let v = v0 + (v1 - v0) * b as f64 / nv as f64;
                    vertices.push(patch.eval(u, v));
                    uv.push([u, v]);
                }
            }
            let id = |a: usize, b: usize| base + (a * (nv + 1) + b) as u32;
            let on_face = part.trim(pi).map(|t| face_cells(t, patch.domain(), nu, nv));
            for a in 0..nu {
                for b in 0..nv {
                    if on_face.as_ref().is_some_and(|c| !c[a * nv + b]) {
                        continue;
                    }
                    triangles.push([id(a, b), id(a + 1, b), id(a + 1, b + 1)]);
                    triangles.push([id(a, b), id(a + 1, b + 1), id(a, b + 1)]);
                    patch_of.extend([pi as u32; 2]);
                }
            }
        }
        let mesh = TriMesh {
            vertices,
            triangles,
        };
        let index = XyIndex::build(&mesh);
        Samples {
            mesh,
            uv,
            patch_of,
            index,
        }
    }

    /// Triangle `t`'s corners as `[x, y, z]`, mm.
    #[inline]
    pub(super) fn corners(&self, t: u32) -> [[f64; 3]; 3] {
        self.mesh.triangles[t as usize].map(|v| {
            let q = self.mesh.vertices[v as usize];
            [q.x, q.y, q.z]
        })
    }

    /// The guess of triangle `t` (corners `p`) at barycentric weights `w`.
    #[inline]
    pub(super) fn guess(&self, t: u32, p: &[[f64; 3]; 3], w: [f64; 3]) -> Guess {
        let uv = self.mesh.triangles[t as usize].map(|v| self.uv[v as usize]);
        Guess {
            z: w[0] * p[0][2] + w[1] * p[1][2] + w[2] * p[2][2],
            uv: [0, 1].map(|d| w[0] * uv[0][d] + w[1] * uv[1][d] + w[2] * uv[2][d]),
            patch: self.patch_of[t as usize],
        }
    }
}

/// Keeps the highest guess of each of the two highest patches.
pub(super) fn keep_top_two(pair: &mut [Guess; 2], g: Guess) {
    if g.patch == pair[0].patch {
        if g.z > pair[0].z {
            pair[0] = g;
        }
    } else if g.patch == pair[1].patch {
        if g.z > pair[1].z {
            pair[1] = g;
        }
        if pair[1].z > pair[0].z {
            pair.swap(0, 1);
        }
    } else if g.z > pair[0].z {
        pair[1] = pair[0];
        pair[0] = g;
    } else if g.z > pair[1].z {
        pair[1] = g;
    }
}

/// Per sample cell `a * nv + b` of a `nu x nv` grid over `domain`, whether any of it
/// may be on the face: a corner inside the loops, or a loop passing through (each loop
/// edge is walked in steps shorter than a cell).
fn face_cells(trim: &Trim, domain: [[f64; 2]; 2], nu: usize, nv: usize) -> Vec<bool> {
    let [[u0, u1], [v0, v1]] = domain;
    let (du, dv) = ((u1 - u0) / nu as f64, (v1 - v0) / nv as f64);
    let mut keep = vec![false; nu * nv];
    let cell = |u: f64, v: f64| {
        let a = (((u - u0) / du).floor().max(0.0) as usize).min(nu - 1);
        let b = (((v - v0) / dv).floor().max(0.0) as usize).min(nv - 1);
        a * nv + b
    };
    for l in trim.loops() {
        for k in 0..l.len() {
            let (p, q) = (l[k], l[(k + 1) % l.len()]);
            let steps = (((q[0] - p[0]) / du).abs() + ((q[1] - p[1]) / dv).abs()).ceil();
            let steps = steps.clamp(1.0, (nu + nv) as f64 * 2.0) as usize;
            for s in 0..=steps {
                let t = s as f64 / steps as f64;
                keep[cell(p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]))] = true;
            }
        }
    }
    for a in 0..=nu {
        for b in 0..=nv {
            let (u, v) = (u0 + du * a as f64, v0 + dv * b as f64);
            if trim.contains(u, v) {
                for (ca, cb) in [(a, b), (a.wrapping_sub(1), b), (a, b.wrapping_sub(1))]
                    .into_iter()
                    .chain([(a.wrapping_sub(1), b.wrapping_sub(1))])
                {
                    if ca < nu && cb < nv {
                        keep[ca * nv + cb] = true;
                    }
                }
            }
        }
    }
    keep
}

/// Samples per direction: control-net length over [`SAMPLE_SPACING`], clamped.
fn sample_counts(patch: &Patch) -> [usize; 2] {
    let [cu, cv] = patch.count();
    let pt = |i: usize, j: usize| patch.point(i, j);
    let along_u = (0..cv)
        .map(|j| {
            (1..cu)
                .map(|i| (pt(i, j) - pt(i - 1, j)).norm())
                .sum::<f64>()
        })
        .fold(0.0, f64::max);
    let along_v = (0..cu)
        .map(|i| {
            (1..cv)
                .map(|j| (pt(i, j) - pt(i, j - 1)).norm())
                .sum::<f64>()
        })
        .fold(0.0, f64::max);
    [along_u, along_v]
        .map(|l| ((l / SAMPLE_SPACING).ceil() as usize).clamp(MIN_SAMPLES, MAX_SAMPLES))
}
