//! The hierarchical mesh drop against brute force on meshes deep enough to use every
//! level of its tree: the shipped meshes and the die, and random dense height fields
//! (smooth, creased, noisy and level, so ties between triangles of equal height are
//! common) with every kind of cutter. Heights are compared bit for bit, with the
//! winning triangle (ties to the lowest index).

use proptest::prelude::*;
use swarf_geom::{Point3, TriMesh};
use swarf_tool::Cutter;
use swarf_tool::drop::{DropCutter, DropScratch, MeshDropper, triangle_drop};

const SPECS: &[&str] = &[
    "flat:d=6",
    "ball:d=8",
    "bull:d=10,r=2",
    "cone:d=10,angle=90",
    "taperball:d=6,angle=10,tip=1,length=12",
    "apt:d=10,r=1.5,alpha=10,beta=5,h=30",
];

/// The highest triangle drop over every triangle, ties to the lowest index.
fn brute(tool: &DropCutter, mesh: &TriMesh, xy: [f64; 2]) -> Option<(u64, usize)> {
    let mut best: Option<(f64, usize)> = None;
    for t in 0..mesh.len() {
        if let Some(d) = triangle_drop(tool, xy, &mesh.triangle(t))
            && best.is_none_or(|b| d.z > b.0)
        {
            best = Some((d.z, t));
        }
    }
    best.map(|(z, t)| (z.to_bits(), t))
}

/// Drops along rows (as a raster does, the scratch's hint carried) and compares.
fn check(mesh: &TriMesh, spec: &str, points: &[[f64; 2]]) -> Result<(), TestCaseError> {
    let cutter: Cutter = spec.parse().unwrap();
    let tool = DropCutter::new(&cutter);
    let dropper = MeshDropper::new(mesh, &cutter);
    let mut scratch = DropScratch::default();
    for &xy in points {
        let got = dropper
            .drop(xy[0], xy[1], &mut scratch)
            .map(|d| (d.z.to_bits(), d.tri as usize));
        prop_assert_eq!(got, brute(&tool, mesh, xy), "{} at {:?}", spec, xy);
    }
    Ok(())
}

/// Rows of points over the XY box of `mesh`, widened by 3 mm, `n` a side.
fn rows(mesh: &TriMesh, n: usize) -> Vec<[f64; 2]> {
    let b = mesh.aabb();
    let (x0, y0) = (b.min.x - 3.0, b.min.y - 3.0);
    let (w, h) = (b.max.x - b.min.x + 6.0, b.max.y - b.min.y + 6.0);
    (0..n * n)
        .map(|k| {
            let (i, j) = ((k % n) as f64 + 0.37, (k / n) as f64 + 0.61);
            [x0 + w * i / n as f64, y0 + h * j / n as f64]
        })
        .collect()
}

#[test]
fn shipped_meshes_drop_as_brute_force() {
    let mut meshes: Vec<(String, TriMesh)> = ["fillet-pocket", "v-grooves", "boss", "ramp-step"]
        .iter()
        .map(|n| (n.to_string(), swarf_io::builtin_mesh(n).unwrap()))
        .collect();
    let die = swarf_io::builtin_part("die")
        .unwrap()
        .tessellate(0.05)
        .unwrap();
    meshes.push(("die".into(), die));
    for (name, mesh) in &meshes {
        for spec in ["ball:d=8", "bull:d=10,r=2", "flat:d=6"] {
            check(mesh, spec, &rows(mesh, 12)).unwrap_or_else(|e| panic!("{name}: {e}"));
        }
    }
}

/// A `n x n` height field over `[0, 40]^2`: a smooth bump, a crease, a level
/// terrace (exact ties) and noise, mixed by the weights given.
fn field(n: usize, w: [f64; 4], noise: Vec<f64>) -> TriMesh {
    let s = 40.0 / (n - 1) as f64;
    let z = |i: usize, j: usize| {
        let (x, y) = (s * i as f64, s * j as f64);
        let bump = 6.0 * (-((x - 18.0).powi(2) + (y - 22.0).powi(2)) / 60.0).exp();
        let crease = -0.4 * (x - 25.0).abs();
        let terrace = if (10.0..30.0).contains(&x) && y < 15.0 {
            3.0
        } else {
            0.0
        };
        w[0] * bump + w[1] * crease + w[2] * terrace + w[3] * noise[(j * n + i) % noise.len()]
    };
    let p = |i: usize, j: usize| Point3::new(s * i as f64, s * j as f64, z(i, j));
    let mut soup = Vec::new();
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            soup.push([p(i, j), p(i + 1, j), p(i + 1, j + 1)]);
            soup.push([p(i, j), p(i + 1, j + 1), p(i, j + 1)]);
        }
    }
    TriMesh::from_triangles(&soup)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    /// Dense random height fields (up to 7,200 triangles, six levels of the tree).
    #[test]
    fn dense_fields_drop_as_brute_force(
        n in 20usize..61,
        w in (0.0..1.0f64, 0.0..1.0f64, 0.0..1.0f64, 0.0..0.3f64),
        noise in prop::collection::vec(-1.0..1.0f64, 1..64),
        which in 0..SPECS.len(),
        start in (0.0..40.0f64, 0.0..40.0f64),
    ) {
        let mesh = field(n, [w.0, w.1, w.2, w.3], noise);
        let points: Vec<[f64; 2]> = (0..40)
            .map(|k| [start.0 + 0.37 * k as f64 - 7.0, start.1 + 0.11 * k as f64 - 2.0])
            .collect();
        check(&mesh, SPECS[which], &points)?;
    }
}
