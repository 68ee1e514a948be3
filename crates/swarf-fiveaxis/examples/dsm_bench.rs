//! Drop-and-spin throughput: `cargo run --release -p swarf-fiveaxis --example
//! dsm_bench`. On both shared edge parts with a bull d = 12, r = 2: the zone at one
//! station, then drops with both spins (each spin a root of the whole-cutter
//! clearance) at footprints across it on 21 stations.

use std::time::Instant;
use swarf_fiveaxis::dsm::{Dsm, SpinSide};
use swarf_geom::Vec3;
use swarf_tool::Cutter;

fn main() {
    let tool: Cutter = "bull:d=12,r=2,length=30".parse().unwrap();
    for name in ["edge-convex", "edge-concave"] {
        let part = swarf_io::builtin_part(name).unwrap();
        let start = Instant::now();
        let dsm = Dsm::new(&part, [0, 1], &tool, Vec3::x()).unwrap();
        let setup = start.elapsed().as_secs_f64();
        let start = Instant::now();
        let st = dsm.station(50.0).unwrap();
        let zone = dsm.zone(&st, 0).unwrap();
        let zone_s = start.elapsed().as_secs_f64();
        let start = Instant::now();
        let mut poses = 0usize;
        for i in 0..=20 {
            let st = dsm.station(5.0 + 4.5 * f64::from(i)).unwrap();
            for k in 0..=8 {
                let w = zone.t1 + (zone.t2 - zone.t1) * f64::from(k) / 10.0;
                let drop = dsm.drop_on(0, dsm.footprint(&st, 0, w)).unwrap();
                for side in [SpinSide::Plus, SpinSide::Minus] {
                    if dsm.spin(&drop, side).is_some() {
                        poses += 1;
                    }
                }
            }
        }
        let t = start.elapsed().as_secs_f64();
        println!(
            "{name}: setup {setup:.3} s, zone {zone_s:.3} s, {poses} spun poses in {t:.3} s: {:.0} poses/s",
            poses as f64 / t
        );
    }
}
