//! The drop tree's layout and search against direct scans.

use super::*;
use proptest::prelude::*;

#[test]
fn order_keys_sort_like_floats() {
    let v = [
        f64::NEG_INFINITY,
        -1e300,
        -2.5,
        -0.0,
        0.0,
        1e-300,
        3.0,
        f64::INFINITY,
    ];
    for w in v.windows(2) {
        assert!(order_key(w[0]) <= order_key(w[1]), "{w:?}");
    }
    for x in v {
        assert_eq!(from_order_key(order_key(x)).to_bits(), x.to_bits());
    }
}

/// Visits everything offered, counting the triangles.
struct All<'a> {
    tree: &'a DropTree,
    seen: Vec<u32>,
    floor: f64,
}

impl Search for All<'_> {
    fn wants(&self, ub: f64) -> bool {
        ub >= self.floor
    }

    fn visit(&mut self, pos: usize) {
        self.seen[self.tree.ids[pos] as usize] += 1;
    }
}

fn soup(tris: &[(f64, f64, f64, f64, u8)]) -> TriMesh {
    let t: Vec<[Point3; 3]> = tris
        .iter()
        .map(|&(x, y, log_s, z, nan)| {
            let s = 10f64.powf(log_s);
            let x0 = if nan == 0 { f64::NAN } else { x };
            [
                Point3::new(x0, y, z),
                Point3::new(x + s, y + 0.3 * s, z + 1.0),
                Point3::new(x + 0.2 * s, y + s, z - 1.0),
            ]
        })
        .collect();
    TriMesh::from_triangles(&t)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]
    /// Every finite triangle with a corner in the disc at or above the floor is
    /// visited exactly once, with its own corners; none is visited twice or
    /// without its box meeting the disc.
    #[test]
    fn search_visits_every_hit_once(
        tris in prop::collection::vec((-40.0..40.0f64, -20.0..20.0f64, -2.0..1.7f64, -5.0..5.0f64, 0u8..30), 1..300),
        q in (-50.0..50.0f64, -30.0..30.0f64, 0.0..12.0f64, -8.0..8.0f64),
    ) {
        let mesh = soup(&tris);
        let tree = DropTree::build(&mesh);
        for pos in 0..tree.len() {
            prop_assert_eq!(tree.corners(pos), mesh.triangle(tree.ids[pos] as usize));
        }
        let mut all = All { tree: &tree, seen: vec![0; mesh.len()], floor: q.3 };
        tree.search([q.0, q.1], q.2, &Flat(q.2), &mut Vec::new(), &mut all);
        for (t, &n) in all.seen.iter().enumerate() {
            let c = mesh.triangle(t);
            if !mesh.usable(t) {
                prop_assert_eq!(n, 0);
                continue;
            }
            let (x0, x1) = (c.iter().map(|p| p.x).fold(f64::MAX, f64::min), c.iter().map(|p| p.x).fold(f64::MIN, f64::max));
            let (y0, y1) = (c.iter().map(|p| p.y).fold(f64::MAX, f64::min), c.iter().map(|p| p.y).fold(f64::MIN, f64::max));
            let d2 = (q.0.clamp(x0, x1) - q.0).powi(2) + (q.1.clamp(y0, y1) - q.1).powi(2);
            let reached = c.iter().any(|p| p.z >= q.3 && (p.x - q.0).hypot(p.y - q.1) <= q.2);
            prop_assert!(n <= 1);
            prop_assert!(n == 0 || d2 <= q.2 * q.2 * (1.0 + 1e-6) + 1e-9);
            if reached {
                prop_assert_eq!(n, 1, "triangle {} missed", t);
            }
        }
    }
}

#[test]
fn empty_and_nan_meshes_store_nothing() {
    let empty = DropTree::build(&TriMesh::default());
    assert_eq!(empty.len(), 0);
    let nan = DropTree::build(&soup(&[(0.0, 0.0, 0.0, 0.0, 0)]));
    assert_eq!(nan.len(), 0);
    let one_mesh = soup(&[(0.0, 0.0, 0.0, 0.0, 1)]);
    let one = DropTree::build(&one_mesh);
    let count = |tree: &DropTree, xy: [f64; 2], r: f64| {
        let mut all = All {
            tree,
            seen: vec![0; 1],
            floor: f64::NEG_INFINITY,
        };
        tree.search(xy, r, &Flat(r), &mut Vec::new(), &mut all);
        all.seen[0]
    };
    assert_eq!(count(&nan, [0.0, 0.0], 1e9), 0);
    assert_eq!(count(&one, [f64::NAN, 0.0], 1.0), 0);
    assert_eq!(count(&one, [0.0, 0.0], -1.0), 0);
    assert_eq!(count(&one, [1e300, 0.0], f64::INFINITY), 1);
    assert!(one.memory_bytes() > 0);
    assert!(one.memory_bytes() <= DropTree::estimate_bytes(&one_mesh));
}
