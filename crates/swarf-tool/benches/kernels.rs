//! Throughput of the kernels that hot loops call: signed distance (the gouge test),
//! height at radius (drop-cutter), pose from contact (planning), profile construction.
//! Peer: the closed-form ball distance `|p - c| - R`, measured in the same run.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use swarf_geom::{Point3, Vec3};
use swarf_tool::{Cutter, Pose};

fn points(n: usize) -> Vec<Point3> {
    (0..n)
        .map(|k| {
            let t = k as f64;
            Point3::new(
                8.0 * (t * 0.37).sin(),
                8.0 * (t * 0.71).cos(),
                12.0 * (t * 0.13).sin(),
            )
        })
        .collect()
}

fn kernels(c: &mut Criterion) {
    let pts = points(1024);
    let pose = Pose::new(Point3::new(0.5, -0.5, 1.0), Vec3::new(0.2, 0.1, 1.0))
        .unwrap_or(Pose::vertical(Point3::origin()));
    let centre = pose.cl + 4.0 * pose.axis;
    c.bench_function("peer: ball closed-form distance x1024", |b| {
        b.iter(|| pts.iter().map(|p| (p - centre).norm() - 4.0).sum::<f64>())
    });
    for spec in [
        "ball:d=8",
        "bull:d=10,r=2",
        "apt:d=10,r=1.5,alpha=10,beta=5",
    ] {
        let cutter: Cutter = spec.parse().unwrap_or(Cutter::Flat {
            radius: 1.0,
            length: 1.0,
        });
        let profile = cutter.profile();
        c.bench_function(&format!("{spec}: Cutter::signed_distance x1024"), |b| {
            b.iter(|| {
                pts.iter()
                    .map(|p| cutter.signed_distance(&pose, p))
                    .sum::<f64>()
            })
        });
        c.bench_function(&format!("{spec}: Profile::signed_distance x1024"), |b| {
            b.iter(|| {
                pts.iter()
                    .map(|p| profile.signed_distance(&pose, p))
                    .sum::<f64>()
            })
        });
        c.bench_function(&format!("{spec}: Profile::height_at_radius x1024"), |b| {
            b.iter(|| {
                pts.iter()
                    .filter_map(|p| profile.height_at_radius(p.x.abs() * 0.6))
                    .sum::<f64>()
            })
        });
        c.bench_function(&format!("{spec}: Cutter::pose_from_contact x1024"), |b| {
            b.iter(|| {
                pts.iter()
                    .filter_map(|p| {
                        let n = Vec3::new(p.x * 0.05, p.y * 0.05, 1.0);
                        cutter.pose_from_contact(p, &n, &pose.axis)
                    })
                    .map(|q| q.cl.z)
                    .sum::<f64>()
            })
        });
        c.bench_function(&format!("{spec}: Cutter::profile"), |b| {
            b.iter(|| black_box(black_box(&cutter).profile()))
        });
    }
}

criterion_group!(benches, kernels);
criterion_main!(benches);
