//! XyIndex build time and `query_disc` throughput on a 100k-triangle heightfield
//! (z = 10 sin(x/10) cos(y/10) on a 0.7 mm grid, about 157 x 157 mm), with the drop-cutter query
//! of a 4.5 mm disc. Peers measured in the same run: the grid at other base cell
//! sizes, and a median-split BVH over the same `f32` boxes (leaf size 4), which must
//! return the same ids. The same mesh with its triangles shuffled shows the cost of
//! sorting hits whose ids are not spatially coherent. Run with `cargo bench -p swarf-geom --bench mesh_index`.

use criterion::{BatchSize, Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use swarf_geom::{Point3, TriMesh, XyIndex};

/// Grid spacing, mm.
const STEP: f64 = 0.7;
/// Squares per side: 2 * 224^2 = 100 352 triangles.
const N: usize = 224;
/// Drop-cutter disc radius, mm.
const RADIUS: f64 = 4.5;
/// Queries per measured batch.
const QUERIES: usize = 1000;

fn heightfield() -> TriMesh {
    let p = |i: usize, j: usize| {
        let (x, y) = (i as f64 * STEP, j as f64 * STEP);
        Point3::new(x, y, (x * 0.1).sin() * (y * 0.1).cos() * 10.0)
    };
    let mut soup = Vec::with_capacity(2 * N * N);
    for j in 0..N {
        for i in 0..N {
            soup.push([p(i, j), p(i + 1, j), p(i + 1, j + 1)]);
            soup.push([p(i, j), p(i + 1, j + 1), p(i, j + 1)]);
        }
    }
    TriMesh::from_triangles(&soup)
}

/// The mesh with its triangle order shuffled (Fisher-Yates on a 64-bit LCG).
fn shuffled(mesh: &TriMesh) -> TriMesh {
    let mut m = mesh.clone();
    let mut s: u64 = 0x9E37_79B9_7F4A_7C15;
    for i in (1..m.triangles.len()).rev() {
        s = s
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        m.triangles.swap(i, (s >> 33) as usize % (i + 1));
    }
    m
}

/// Deterministic pseudo-random centres over the mesh (a 64-bit LCG).
fn centres(n: usize) -> Vec<[f64; 2]> {
    let mut s: u64 = 0x2545_F491_4F6C_DD1D;
    let mut next = || {
        s = s
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (s >> 11) as f64 / (1u64 << 53) as f64 * N as f64 * STEP
    };
    (0..n).map(|_| [next(), next()]).collect()
}

/// The peer: a BVH over `[min_x, min_y, max_x, max_y]` boxes, median split on the
/// longer axis of the centres, nodes in depth-first order.
struct Bvh {
    nodes: Vec<Node>,
    ids: Vec<u32>,
    boxes: Vec<[f32; 4]>,
}

struct Node {
    bbox: [f32; 4],
    /// Leaf: `start..start + count` into `ids`; inner (count 0): right child index.
    start: u32,
    count: u32,
}

impl Bvh {
    fn build(mesh: &TriMesh) -> Bvh {
        let boxes: Vec<[f32; 4]> = (0..mesh.len())
            .map(|t| {
                let c = mesh.triangle(t);
                let lo = |a: usize| c.iter().map(|p| p[a]).fold(f64::MAX, f64::min) as f32;
                let hi = |a: usize| c.iter().map(|p| p[a]).fold(f64::MIN, f64::max) as f32;
                [lo(0), lo(1), hi(0), hi(1)]
            })
            .collect();
        let mut bvh = Bvh {
            nodes: Vec::new(),
            ids: (0..mesh.len() as u32).collect(),
            boxes,
        };
        bvh.split(0, mesh.len());
        bvh
    }

    fn split(&mut self, start: usize, end: usize) -> usize {
        let b =
            self.ids[start..end]
                .iter()
                .fold([f32::MAX, f32::MAX, f32::MIN, f32::MIN], |a, &t| {
                    let x = self.boxes[t as usize];
                    [
                        a[0].min(x[0]),
                        a[1].min(x[1]),
                        a[2].max(x[2]),
                        a[3].max(x[3]),
                    ]
                });
        let me = self.nodes.len();
        self.nodes.push(Node {
            bbox: b,
            start: start as u32,
            count: (end - start) as u32,
        });
        if end - start > 4 {
            let axis = usize::from(b[3] - b[1] > b[2] - b[0]);
            let boxes = &self.boxes;
            let mid = (start + end) / 2;
            self.ids[start..end].select_nth_unstable_by(mid - start, |&p, &q| {
                let c = |t: u32| boxes[t as usize][axis] + boxes[t as usize][axis + 2];
                c(p).total_cmp(&c(q))
            });
            self.split(start, mid);
            let right = self.split(mid, end);
            self.nodes[me].count = 0;
            self.nodes[me].start = right as u32;
        }
        me
    }

    fn query_disc(&self, c: [f64; 2], r: f64, out: &mut Vec<u32>, sorted: bool) {
        out.clear();
        let meets = |b: &[f32; 4]| {
            let dx = (f64::from(b[0]) - c[0])
                .max(c[0] - f64::from(b[2]))
                .max(0.0);
            let dy = (f64::from(b[1]) - c[1])
                .max(c[1] - f64::from(b[3]))
                .max(0.0);
            dx * dx + dy * dy <= r * r
        };
        let mut stack = vec![0usize];
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n];
            if !meets(&node.bbox) {
                continue;
            }
            if node.count == 0 {
                stack.push(node.start as usize);
                stack.push(n + 1);
            } else {
                let run = node.start as usize..(node.start + node.count) as usize;
                out.extend(
                    self.ids[run]
                        .iter()
                        .filter(|&&t| meets(&self.boxes[t as usize])),
                );
            }
        }
        if sorted {
            out.sort_unstable();
        }
    }
}

/// The grid and the BVH peer agree on every query (the grid may add up to two
/// triangles the BVH's exact test leaves out); prints the hit rate and index size.
fn check_agreement(mesh: &TriMesh, qs: &[[f64; 2]], index: &XyIndex, bvh: &Bvh) {
    let (mut a, mut b, mut hits) = (Vec::new(), Vec::new(), 0);
    for q in qs {
        index.query_disc(*q, RADIUS, &mut a);
        bvh.query_disc(*q, RADIUS, &mut b, true);
        assert!(
            b.iter().all(|t| a.binary_search(t).is_ok()),
            "BVH found a triangle the grid missed"
        );
        assert!(
            a.len() - b.len() <= 2,
            "grid returned {} more than the BVH",
            a.len() - b.len()
        );
        hits += a.len();
    }
    eprintln!(
        "mesh_index: {} triangles, {:.1} hits/query, index {} bytes = {:.1} bytes/triangle",
        mesh.len(),
        hits as f64 / QUERIES as f64,
        index.memory_bytes(),
        index.memory_bytes() as f64 / mesh.len() as f64
    );
}

fn bench(c: &mut Criterion) {
    let mesh = heightfield();
    let qs = centres(QUERIES);
    let index = XyIndex::build(&mesh);
    let bvh = Bvh::build(&mesh);
    check_agreement(&mesh, &qs, &index, &bvh);

    let mut g = c.benchmark_group("mesh_index_build");
    g.sample_size(10);
    g.throughput(Throughput::Elements(mesh.len() as u64));
    g.bench_function("grid", |bch| bch.iter(|| XyIndex::build(black_box(&mesh))));
    g.bench_function("bvh_peer", |bch| bch.iter(|| Bvh::build(black_box(&mesh))));
    g.finish();

    let mut g = c.benchmark_group("mesh_index_query_disc_r4.5");
    g.throughput(Throughput::Elements(QUERIES as u64));
    g.bench_function("grid_query_disc_sorted", |bch| {
        bch.iter_batched_ref(
            Vec::new,
            |out| qs.iter().for_each(|q| index.query_disc(*q, RADIUS, out)),
            BatchSize::SmallInput,
        )
    });
    g.bench_function("grid_for_each_in_disc", |bch| {
        bch.iter(|| {
            let mut sum = 0u64;
            for q in &qs {
                index.for_each_in_disc(*q, RADIUS, |t| sum += u64::from(t));
            }
            sum
        })
    });
    let shuffled_mesh = shuffled(&mesh);
    let shuffled_index = XyIndex::build(&shuffled_mesh);
    g.bench_function("grid_query_disc_sorted_shuffled", |bch| {
        bch.iter_batched_ref(
            Vec::new,
            |out| {
                qs.iter()
                    .for_each(|q| shuffled_index.query_disc(*q, RADIUS, out))
            },
            BatchSize::SmallInput,
        )
    });
    g.bench_function("grid_for_each_in_disc_shuffled", |bch| {
        bch.iter(|| {
            let mut sum = 0u64;
            for q in &qs {
                shuffled_index.for_each_in_disc(*q, RADIUS, |t| sum += u64::from(t));
            }
            sum
        })
    });
    for factor in [1.0, 2.0, 4.0] {
        let idx = XyIndex::build_with_cell_size(&mesh, Some(STEP * factor));
        g.bench_function(format!("grid_for_each_cell_{factor}x"), |bch| {
            bch.iter(|| {
                let mut sum = 0u64;
                for q in &qs {
                    idx.for_each_in_disc(*q, RADIUS, |t| sum += u64::from(t));
                }
                sum
            })
        });
    }
    for sorted in [true, false] {
        g.bench_function(format!("bvh_peer_sorted_{sorted}"), |bch| {
            bch.iter_batched_ref(
                Vec::new,
                |out| {
                    qs.iter()
                        .for_each(|q| bvh.query_disc(*q, RADIUS, out, sorted))
                },
                BatchSize::SmallInput,
            )
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
