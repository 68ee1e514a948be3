//! Patch kernel throughput on parts/wave.toml (bicubic Bezier) and an exact NURBS sphere
//! octant (biquadratic rational): `derivs` (point + exact first and second partials) and
//! `eval` in points/s, against a peer measured in the same run (textbook de Casteljau
//! in both directions on heap-allocated rows, the common hand-written alternative);
//! `project` in points/s; tessellation of wave within 0.01 mm; a plane section of wave
//! within 0.01 mm. Run with `cargo bench -p swarf-geom --bench patch`.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use swarf_geom::{Patch, Plane, Point3, Vec3};

/// Parameter samples per direction in one measured batch (64 x 64 = 4096 points).
const N: usize = 64;

fn wave() -> Patch {
    let raw: [[f64; 3]; 16] = [
        [0.0, 0.0, 6.0],
        [0.0, 20.0, 28.0],
        [0.0, 60.0, 38.0],
        [0.0, 100.0, 15.0],
        [30.0, 0.0, 23.0],
        [30.0, 20.0, 62.0],
        [30.0, 60.0, 72.0],
        [30.0, 100.0, 38.0],
        [110.0, 0.0, 18.0],
        [110.0, 20.0, 59.0],
        [110.0, 60.0, 74.0],
        [110.0, 100.0, 33.0],
        [200.0, 0.0, 0.0],
        [200.0, 20.0, 20.0],
        [200.0, 60.0, 36.0],
        [200.0, 100.0, 10.0],
    ];
    let pts = raw.iter().map(|p| Point3::new(p[0], p[1], p[2])).collect();
    Patch::bezier([3, 3], pts).expect("wave")
}

fn sphere_octant(r: f64) -> Patch {
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let mut p = Vec::new();
    let mut w = Vec::new();
    for (rad, z, wm) in [(r, 0.0, 1.0), (r, r, s), (0.0, r, 1.0)] {
        for (cx, cy, wa) in [(1.0, 0.0, 1.0), (1.0, 1.0, s), (0.0, 1.0, 1.0)] {
            p.push(Point3::new(rad * cx, rad * cy, z));
            w.push(wm * wa);
        }
    }
    Patch::new([2, 2], p, [None, None], Some(w)).expect("sphere")
}

fn params() -> Vec<(f64, f64)> {
    (0..N)
        .flat_map(|i| {
            (0..N).map(move |j| ((i as f64 + 0.5) / N as f64, (j as f64 + 0.37) / N as f64))
        })
        .collect()
}

/// The peer: de Casteljau on each row, then on the column of results (allocating).
fn de_casteljau(p: &Patch, u: f64, v: f64) -> Point3 {
    let [nu, nv] = p.count();
    let curve = |mut c: Vec<Vec3>, t: f64| {
        for k in (1..c.len()).rev() {
            for i in 0..k {
                c[i] = c[i] * (1.0 - t) + c[i + 1] * t;
            }
        }
        c[0]
    };
    let rows: Vec<Vec3> = (0..nu)
        .map(|i| curve((0..nv).map(|j| p.point(i, j).coords).collect(), v))
        .collect();
    Point3::from(curve(rows, u))
}

fn evaluation(c: &mut Criterion) {
    let uv = params();
    let mut g = c.benchmark_group("evaluation");
    g.throughput(Throughput::Elements(uv.len() as u64));
    for (name, patch) in [("wave", wave()), ("sphere", sphere_octant(10.0))] {
        g.bench_function(format!("derivs/{name}"), |b| {
            b.iter(|| {
                for &(u, v) in &uv {
                    black_box(patch.derivs(black_box(u), black_box(v)));
                }
            })
        });
        g.bench_function(format!("eval/{name}"), |b| {
            b.iter(|| {
                for &(u, v) in &uv {
                    black_box(patch.eval(black_box(u), black_box(v)));
                }
            })
        });
    }
    let w = wave();
    g.bench_function("de_casteljau_peer/wave", |b| {
        b.iter(|| {
            for &(u, v) in &uv {
                black_box(de_casteljau(&w, black_box(u), black_box(v)));
            }
        })
    });
    g.finish();
}

fn queries(c: &mut Criterion) {
    let w = wave();
    let points: Vec<Point3> = params()
        .iter()
        .step_by(16)
        .map(|&(u, v)| {
            let d = w.derivs(u, v);
            d.point + d.normal().unwrap_or_else(Vec3::z) * (10.0 * (u - v))
        })
        .collect();
    let mut g = c.benchmark_group("queries");
    g.throughput(Throughput::Elements(points.len() as u64));
    g.bench_function("project/wave", |b| {
        b.iter(|| {
            for p in &points {
                black_box(w.project(black_box(p)));
            }
        })
    });
    g.finish();
    let mut g = c.benchmark_group("meshing");
    g.sample_size(10);
    g.bench_function("tessellate/wave/0.01mm", |b| {
        b.iter(|| black_box(w.tessellate(black_box(0.01)).expect("mesh")))
    });
    let plane = Plane::from_point_normal(&Point3::new(0.0, 0.0, 40.0), &Vec3::new(0.1, 0.2, 1.0))
        .expect("plane");
    g.bench_function("intersect_plane/wave/0.01mm", |b| {
        b.iter(|| black_box(w.intersect_plane(black_box(&plane), 0.01).expect("section")))
    });
    g.finish();
}

criterion_group!(benches, evaluation, queries);
criterion_main!(benches);
