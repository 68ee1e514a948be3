//! Seed meshes (binary STL, ASCII STL, OBJ) and structure-aware mutations of binary
//! STL: a float of a normal or vertex set to NaN, an infinity, f32::MAX or a
//! subnormal; the triangle count in the header made to lie; triangles collapsed,
//! duplicated or dropped; and the byte-level edits of [`crate::mutate`]. Then the
//! cases: a mutated mesh read by `inspect`, `drop`, `classify`, `verify`, `rest` and
//! a raster job's `plan`.

use crate::cases::{Edit, case, file};
use crate::exec::Case;
use crate::mutate::{self, Mutation, apply_all};
use crate::seeds;
use proptest::prelude::*;

/// A bumpy height field over [0, 40] x [0, 40] mm: `n` x `n` cells, two triangles
/// each, counter-clockwise seen from above.
pub fn height_field(n: usize) -> Vec<[[f32; 3]; 3]> {
    let step = 40.0 / n as f32;
    let p = |i: usize, j: usize| {
        let (x, y) = (i as f32 * step, j as f32 * step);
        [x, y, 10.0 + 5.0 * (x / 6.0).sin() * (y / 8.0).cos()]
    };
    let mut tris = Vec::new();
    for j in 0..n {
        for i in 0..n {
            tris.push([p(i, j), p(i + 1, j), p(i + 1, j + 1)]);
            tris.push([p(i, j), p(i + 1, j + 1), p(i, j + 1)]);
        }
    }
    tris
}

fn normal(t: &[[f32; 3]; 3]) -> [f32; 3] {
    let u = [t[1][0] - t[0][0], t[1][1] - t[0][1], t[1][2] - t[0][2]];
    let v = [t[2][0] - t[0][0], t[2][1] - t[0][1], t[2][2] - t[0][2]];
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt().max(1e-30);
    [n[0] / l, n[1] / l, n[2] / l]
}

/// Binary STL: an 80-byte header, the triangle count, 50 bytes per triangle.
pub fn binary_stl(tris: &[[[f32; 3]; 3]]) -> Vec<u8> {
    let mut out = b"swarf fuzz seed".to_vec();
    out.resize(80, b' ');
    out.extend_from_slice(&(tris.len() as u32).to_le_bytes());
    for t in tris {
        for f in normal(t).iter().chain(t.iter().flatten()) {
            out.extend_from_slice(&f.to_le_bytes());
        }
        out.extend_from_slice(&[0, 0]);
    }
    out
}

/// ASCII STL of the same triangles.
pub fn ascii_stl(tris: &[[[f32; 3]; 3]]) -> Vec<u8> {
    let mut s = String::from("solid seed\n");
    for t in tris {
        let n = normal(t);
        s += &format!(
            "  facet normal {} {} {}\n    outer loop\n",
            n[0], n[1], n[2]
        );
        for v in t {
            s += &format!("      vertex {} {} {}\n", v[0], v[1], v[2]);
        }
        s += "    endloop\n  endfacet\n";
    }
    s += "endsolid seed\n";
    s.into_bytes()
}

/// OBJ of the same triangles, with shared vertices and 1-based faces.
pub fn obj(n: usize) -> Vec<u8> {
    let step = 40.0 / n as f64;
    let mut s = String::from("# swarf fuzz seed\no seed\n");
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f64 * step, j as f64 * step);
            let z = 10.0 + 5.0 * (x / 6.0).sin() * (y / 8.0).cos();
            s += &format!("v {x} {y} {z:.6}\n");
        }
    }
    let id = |i: usize, j: usize| j * (n + 1) + i + 1;
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            s += &format!("f {a} {b} {c}\nf {a} {c} {d}\n");
        }
    }
    s.into_bytes()
}

/// One edit of a binary STL.
#[derive(Debug, Clone)]
pub enum StlMutation {
    /// Set float `k` (modulo the floats of all triangles: normal, then 3 vertices).
    Float { k: usize, value: f32 },
    /// Write `count` as the triangle count in the header.
    Count { count: u32 },
    /// Move all three vertices of triangle `t` onto its first.
    Collapse { t: usize },
    /// Repeat triangle `t` `times` more times (the count follows).
    Duplicate { t: usize, times: usize },
    /// Drop triangle `t`, leaving the count as it was.
    Drop { t: usize },
    /// A byte-level edit.
    Bytes(Mutation),
}

/// Floats that break geometry.
const FLOATS: &[f32] = &[
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    f32::MAX,
    f32::MIN,
    f32::MIN_POSITIVE,
    1e-45,
    0.0,
    -0.0,
    1e30,
    -1e30,
    1e-30,
];

/// Any one binary STL edit.
pub fn stl_mutation() -> impl Strategy<Value = StlMutation> {
    let k = 0usize..100_000;
    prop_oneof![
        8 => (k.clone(), prop_oneof![3 => prop::sample::select(FLOATS), 1 => any::<f32>()])
            .prop_map(|(k, value)| StlMutation::Float { k, value }),
        2 => prop_oneof![
            Just(0u32), Just(1), Just(u32::MAX), Just(1 << 28), any::<u32>()
        ].prop_map(|count| StlMutation::Count { count }),
        2 => k.clone().prop_map(|t| StlMutation::Collapse { t }),
        1 => (k.clone(), prop_oneof![Just(1usize), Just(10_000)])
            .prop_map(|(t, times)| StlMutation::Duplicate { t, times }),
        1 => k.prop_map(|t| StlMutation::Drop { t }),
        2 => prop_oneof![
            (0u16..=1000).prop_map(|permille| Mutation::Truncate { permille }),
            ((0u16..=1000), prop::collection::vec(any::<u8>(), 1..64))
                .prop_map(|(permille, bytes)| Mutation::Garbage { permille, bytes }),
            Just(Mutation::Empty),
        ].prop_map(StlMutation::Bytes),
    ]
}

/// `stl` (a binary STL) with `m` applied.
pub fn apply_stl(stl: &[u8], m: &StlMutation) -> Vec<u8> {
    const HEAD: usize = 84;
    const TRI: usize = 50;
    let mut out = stl.to_vec();
    let tris = stl.len().saturating_sub(HEAD) / TRI;
    let set_count = |out: &mut Vec<u8>, n: usize| {
        if out.len() >= HEAD {
            out[80..84].copy_from_slice(&(n as u32).to_le_bytes());
        }
    };
    match m {
        StlMutation::Bytes(b) => return mutate::apply(stl, b),
        StlMutation::Count { count } => set_count(&mut out, *count as usize),
        _ if tris == 0 => {}
        StlMutation::Float { k, value } => {
            let k = k % (tris * 12);
            let at = HEAD + (k / 12) * TRI + (k % 12) * 4;
            out[at..at + 4].copy_from_slice(&value.to_le_bytes());
        }
        StlMutation::Collapse { t } => {
            let at = HEAD + (t % tris) * TRI + 12;
            let first = out[at..at + 12].to_vec();
            out[at + 12..at + 24].copy_from_slice(&first);
            out[at + 24..at + 36].copy_from_slice(&first);
        }
        StlMutation::Duplicate { t, times } => {
            let at = HEAD + (t % tris) * TRI;
            let tri = out[at..at + TRI].to_vec();
            let extra: Vec<u8> = tri.repeat(*times);
            out.splice(at..at, extra);
            set_count(&mut out, tris + times);
        }
        StlMutation::Drop { t } => {
            let at = HEAD + (t % tris) * TRI;
            out.drain(at..at + TRI);
        }
    }
    out
}

/// A raster job on mesh file `m`.
fn mesh_job(m: &str) -> String {
    format!(
        "name = \"mesh raster\"\npart = \"{m}\"\ntool = \"ball:d=6\"\n\n[strategy]\n\
         kind = \"raster\"\nscallop = 0.2\ntolerance = 0.02\n\n[output]\ngcode = \"m.ngc\"\n\
         summary = \"m.json\"\n"
    )
}

/// A mesh file `m` (already mutated), read by every command that takes a mesh.
pub fn mesh_case(m: &str, bytes: Vec<u8>, cmd: usize, about: String) -> Case {
    let mut files = vec![(m.to_string(), bytes)];
    match cmd % 6 {
        0 => case("inspect", &["inspect", m], files, &[m], about),
        1 => {
            files.push(file("points.csv", "x,y\n10,10\n20,25\n39,1\n-30,5\n"));
            let args = [
                "drop",
                "--mesh",
                m,
                "--tool=ball:d=4",
                "--points",
                "points.csv",
                "--contact",
            ];
            case("drop", &args, files, &[m], about)
        }
        2 => case(
            "classify",
            &["classify", m, "--cell=1", "-o", "out"],
            files,
            &[m],
            about,
        ),
        3 => {
            files.push(file("pass.ngc", seeds::MESH_PROGRAM));
            let args = [
                "verify",
                "--part",
                m,
                "--program",
                "pass.ngc",
                "--tool=ball:d=4",
                "--cell=0.5",
                "--max-memory=1024",
                "-o",
                "out",
            ];
            case("verify", &args, files, &[m], about)
        }
        4 => {
            let args = ["rest", "--part", m, "--reference=ball:d=10", "-o", "out"];
            case("rest", &args, files, &[m], about)
        }
        _ => {
            files.push(file("mesh-job.toml", &mesh_job(m)));
            let args = ["plan", "mesh-job.toml", "--out", "out"];
            case("plan", &args, files, &[m, "mesh-job.toml"], about)
        }
    }
}

/// Binary STL edits and a command index.
pub fn stl_edit() -> impl Strategy<Value = (Vec<StlMutation>, usize)> {
    (prop::collection::vec(stl_mutation(), 1..=3), 0usize..1000)
}

/// A binary STL with structure-aware edits.
pub fn binary_stl_case((ms, cmd): &(Vec<StlMutation>, usize)) -> Case {
    let seed = binary_stl(&height_field(8));
    let bytes = ms.iter().fold(seed, |b, m| apply_stl(&b, m));
    let about = format!("seed: 8 x 8 height field, 128 triangles; edits {ms:?}");
    mesh_case("mesh.stl", bytes, *cmd, about)
}

/// An ASCII STL or OBJ with text edits.
pub fn text_mesh(name: &str, seed: &[u8], (_, ms, cmd): &Edit) -> Case {
    let about = format!("seed: 8 x 8 height field ({name}); edits {ms:?}");
    mesh_case(name, apply_all(seed, ms), *cmd, about)
}
