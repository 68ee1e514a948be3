//! Drop-cutter benchmarks on the shared parts.
//!
//! - `mesh/*`: one thread, drops over a 0.5 mm grid of points in input order (as a
//!   raster or `swarf drop` runs them): ball d=8 on die.toml tessellated to ~78,000
//!   triangles, bull d=10 r=2 on wave.toml tessellated to ~180,000 triangles. The
//!   `xyindex_peer` variant runs the flat scan over `swarf_geom::XyIndex` (every
//!   triangle in the cutter's disc bounded by its top, the candidates from a heap),
//!   to measure what the drop tree's bounds buy (`drop/tree`). The growth with the
//!   mesh's density is `tools/ocl/bench_dense.py`.
//! - `kernel/*`: `triangle_drop` alone over (point, triangle) pairs within reach taken
//!   from the same meshes: the time of one triangle-cutter test, the floor a drop
//!   approaches.
//!
//! The comparison with OpenCAMLib (same mesh, same points, 2 threads) is
//! `tools/ocl/bench_drop.py`.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::collections::BinaryHeap;
use std::hint::black_box;
use swarf_geom::{TriMesh, XyIndex};
use swarf_tool::Cutter;
use swarf_tool::drop::{DropCutter, DropScratch, MeshDropper, triangle_drop, triangle_drop_above};

/// Points per measured batch.
const BATCH: usize = 4000;

fn tessellated(name: &str, tol: f64) -> TriMesh {
    swarf_io::builtin_part(name)
        .expect("built-in part")
        .tessellate(tol)
        .expect("tessellation")
}

/// A 0.5 mm grid over the middle of the mesh's XY box, `BATCH` points row by row.
fn grid(mesh: &TriMesh) -> Vec<[f64; 2]> {
    let b = mesh.aabb();
    let c = b.center();
    let n = (BATCH as f64).sqrt() as usize;
    let half = 0.25 * n as f64;
    (0..n * n)
        .map(|k| {
            let (i, j) = ((k % n) as f64, (k / n) as f64);
            [c.x - half + 0.5 * i, c.y - half + 0.5 * j]
        })
        .collect()
}

/// The same drop over `XyIndex`: the peer of `MeshDropper`, with the same algorithm
/// (last-winner hint, height bound `z_max - h(rho_min)`, candidates from a heap in
/// descending bound, `triangle_drop_above`), but the shared index's ids, a separate
/// array of tops and the corners fetched through the mesh's vertex list.
struct IndexPeer<'a> {
    mesh: &'a TriMesh,
    index: XyIndex,
    zmax: Vec<f64>,
    tool: DropCutter,
}

impl IndexPeer<'_> {
    fn drop(
        &self,
        xy: [f64; 2],
        hint: &mut Option<u32>,
        heap: &mut BinaryHeap<(u64, u32)>,
    ) -> Option<f64> {
        let mut best: Option<(f64, u32)> = None;
        let consider = |t: u32, floor: f64, best: &mut Option<(f64, u32)>| {
            let tri = self.mesh.triangle(t as usize);
            if let Some(c) = triangle_drop_above(&self.tool, xy, &tri, floor)
                && best.is_none_or(|b| c.z > b.0 || (c.z == b.0 && t < b.1))
            {
                *best = Some((c.z, t));
            }
        };
        if let Some(t) = hint.take() {
            consider(t, f64::NEG_INFINITY, &mut best);
        }
        let seed = best.map_or(f64::NEG_INFINITY, |b| b.0);
        let env = self.tool.envelope();
        heap.clear();
        self.index.for_each_in_disc(xy, self.tool.radius(), |t| {
            let top = self.zmax[t as usize];
            if top < seed {
                return;
            }
            let c = self.mesh.triangle(t as usize);
            let lo = |a: usize| c[0][a].min(c[1][a]).min(c[2][a]);
            let hi = |a: usize| c[0][a].max(c[1][a]).max(c[2][a]);
            let dx = (lo(0) - xy[0]).max(xy[0] - hi(0)).max(0.0);
            let dy = (lo(1) - xy[1]).max(xy[1] - hi(1)).max(0.0);
            let ub = top - env.height((dx * dx + dy * dy).sqrt().min(self.tool.radius()));
            if ub >= seed {
                heap.push((ordered(ub), t));
            }
        });
        while let Some((key, t)) = heap.pop() {
            let floor = best.map_or(f64::NEG_INFINITY, |b| b.0);
            if unordered(key) < floor {
                break;
            }
            consider(t, floor, &mut best);
        }
        *hint = best.map(|b| b.1);
        best.map(|b| b.0)
    }
}

fn ordered(v: f64) -> u64 {
    let b = v.to_bits();
    if b >> 63 == 1 { !b } else { b | (1 << 63) }
}

fn unordered(k: u64) -> f64 {
    f64::from_bits(if k >> 63 == 1 { k & !(1 << 63) } else { !k })
}

fn mesh_case(c: &mut Criterion, name: &str, mesh: &TriMesh, spec: &str) {
    let cutter: Cutter = spec.parse().expect("spec");
    let dropper = MeshDropper::new(mesh, &cutter);
    let pts = grid(mesh);
    let mut group = c.benchmark_group(format!("mesh/{name}"));
    group.throughput(Throughput::Elements(pts.len() as u64));
    group.sample_size(20);
    group.bench_function("drop_tree", |b| {
        let mut s = DropScratch::default();
        b.iter(|| {
            for p in &pts {
                black_box(dropper.drop(p[0], p[1], &mut s));
            }
        });
    });
    let peer = IndexPeer {
        mesh,
        index: XyIndex::build(mesh),
        zmax: (0..mesh.len())
            .map(|t| {
                mesh.triangle(t)
                    .iter()
                    .map(|p| p.z)
                    .fold(f64::MIN, f64::max)
            })
            .collect(),
        tool: DropCutter::new(&cutter),
    };
    let mut s = DropScratch::default();
    let (mut hint, mut heap) = (None, BinaryHeap::new());
    for p in pts.iter().step_by(7) {
        let ours = dropper.drop(p[0], p[1], &mut s).map(|d| d.z);
        assert_eq!(
            ours,
            peer.drop(*p, &mut hint, &mut heap),
            "peer disagrees at {p:?}"
        );
    }
    group.bench_function("xyindex_peer", |b| {
        b.iter(|| {
            for p in &pts {
                black_box(peer.drop(*p, &mut hint, &mut heap));
            }
        });
    });
    group.finish();
    kernel_case(c, name, mesh, &cutter, &pts);
}

/// `triangle_drop` over the (point, triangle) pairs within reach.
fn kernel_case(c: &mut Criterion, name: &str, mesh: &TriMesh, cutter: &Cutter, pts: &[[f64; 2]]) {
    let tool = DropCutter::new(cutter);
    let index = XyIndex::build(mesh);
    let mut pairs = Vec::new();
    for p in pts.iter().step_by(40) {
        index.for_each_in_disc(*p, tool.radius(), |t| {
            pairs.push((*p, mesh.triangle(t as usize)))
        });
    }
    let mut group = c.benchmark_group(format!("kernel/{name}"));
    group.throughput(Throughput::Elements(pairs.len() as u64));
    group.sample_size(20);
    group.bench_function("triangle_drop", |b| {
        b.iter(|| {
            for (p, t) in &pairs {
                black_box(triangle_drop(&tool, *p, t));
            }
        });
    });
    group.finish();
}

fn benches(c: &mut Criterion) {
    let die = tessellated("die", 0.0008);
    mesh_case(c, "die78k_ball8", &die, "ball:d=8");
    let wave = tessellated("wave", 0.001);
    mesh_case(c, "wave180k_bull10r2", &wave, "bull:d=10,r=2");
}

criterion_group!(drop_benches, benches);
criterion_main!(drop_benches);
