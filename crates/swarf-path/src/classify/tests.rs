//! Tests of the classification on the built-in `boss` (walls at 45, 65, 80 and 90
//! degrees; closed forms from the part's description, not from the code) and on
//! plain plates.

use super::*;
use geo::{Area, BooleanOps, Contains, Intersects, Point};
use swarf_geom::Point3;

fn boss() -> TriMesh {
    swarf_io::builtin_mesh("boss").unwrap()
}

/// The boss's walls: (angle in degrees, horizontal run of one side in mm); each rib
/// is 80 long and has two sides 10 high.
const WALLS: [(f64, f64); 4] = [
    (45.0, 10.0),
    (65.0, 4.663077),
    (80.0, 1.763270),
    (90.0, 0.0),
];

fn deg(d: f64) -> f64 {
    d.to_radians()
}

/// 3D area, XY area and XY perimeter of the boss's walls steeper than `min_deg`:
/// per side 80 x 10 / sin a, 80 x run, and a strip 80 by run (a segment of
/// perimeter 160 when vertical).
fn walls_above(min_deg: f64) -> (f64, f64, f64) {
    WALLS
        .iter()
        .filter(|w| w.0 > min_deg)
        .fold((0.0, 0.0, 0.0), |(s, xy, per), &(a, run)| {
            (
                s + 2.0 * 800.0 / deg(a).sin(),
                xy + 2.0 * 80.0 * run,
                per + 2.0 * 2.0 * (80.0 + run),
            )
        })
}

/// Across passes fed at `phi` a wall of slope `a` facing y slopes by `s` with
/// `sin s = sin a cos phi`: at 45 degrees the 40-degree limit keeps the walls above
/// `asin(sin 40 / cos 45)` = 65.4 degrees; passes along y see no wall at all.
#[test]
fn slopes_across_the_feed_are_what_a_raster_sees() {
    let mesh = boss();
    let across = |phi: f64| {
        let params = ClassifyParams {
            feed_angle: Some(deg(phi)),
            ..ClassifyParams::default()
        };
        classify(&mesh, &params).unwrap()
    };
    let limit = (deg(40.0).sin() / deg(45.0).cos()).asin().to_degrees();
    for (phi, min_deg) in [(0.0, 40.0), (180.0, 40.0), (45.0, limit), (-45.0, limit)] {
        let c = across(phi);
        let (surface, _, _) = walls_above(min_deg);
        assert!(
            (c.steep.surface_area - surface).abs() < 1e-6,
            "{phi}: {:?}",
            c.steep
        );
    }
    let along = across(90.0);
    assert_eq!((along.steep.cells, along.steep.triangles), (0, 0));
    // Every wall then slopes 0 across the passes: horizontal, as the floor.
    assert_eq!(
        (along.horizontal.triangles, along.other.triangles),
        (mesh.len(), 0)
    );
    let e = classify(
        &mesh,
        &ClassifyParams {
            feed_angle: Some(f64::NAN),
            ..ClassifyParams::default()
        },
    )
    .unwrap_err();
    assert!(e.to_string().contains("classify.feed_angle"), "{e}");
}

fn plate(size: f64, z: impl Fn(f64, f64) -> f64) -> TriMesh {
    let p = |x: f64, y: f64| Point3::new(x, y, z(x, y));
    let n = 8;
    let s = size / n as f64;
    let mut tris = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (i as f64 * s, j as f64 * s);
            let [a, b, c, d] = [p(x, y), p(x + s, y), p(x + s, y + s), p(x, y + s)];
            tris.extend([[a, b, c], [a, c, d]]);
        }
    }
    TriMesh::from_triangles(&tris)
}

#[test]
fn boss_steep_areas_match_the_walls() {
    let mesh = boss();
    for (steep_deg, cell) in [(40.0, 1.0), (40.0, 0.35), (70.0, 1.0)] {
        let params = ClassifyParams {
            steep_angle: deg(steep_deg),
            cell,
            ..ClassifyParams::default()
        };
        let c = classify(&mesh, &params).unwrap();
        let (surface, xy, perimeter) = walls_above(steep_deg);
        let s = &c.steep;
        assert!(
            (s.surface_area - surface).abs() < 1e-6,
            "{steep_deg}: {s:?}"
        );
        let band = perimeter * cell;
        println!(
            "steep {steep_deg} deg, cell {cell}: steep XY {:.3} against {xy:.3} (band {band:.1}), \
             horizontal {:.3}, other {:.3}",
            s.xy_area, c.horizontal.xy_area, c.other.xy_area
        );
        assert!(
            s.xy_area >= xy - 1e-6 && s.xy_area <= xy + band,
            "{}",
            s.xy_area
        );
        let walls = WALLS.iter().filter(|w| w.0 > steep_deg).count();
        assert_eq!(s.triangles, 4 * walls);
        let tilted = WALLS.iter().filter(|w| w.0 <= steep_deg).count();
        assert_eq!(c.other.triangles, 4 * tilted);
        assert_eq!((c.degenerate, c.facing_down), (0, 0));
        // The three regions tile the plate without overlap.
        let total = s.xy_area + c.horizontal.xy_area + c.other.xy_area;
        assert!((total - 80.0 * 140.0).abs() < 1e-3, "{total}");
        let overlap = s.region.intersection(&c.horizontal.region).unsigned_area()
            + s.region.intersection(&c.other.region).unsigned_area()
            + c.horizontal
                .region
                .intersection(&c.other.region)
                .unsigned_area();
        assert!(overlap < 1e-6, "{overlap}");
    }
}

#[test]
fn every_steep_centroid_lies_in_the_steep_region() {
    let mesh = boss();
    let c = classify(&mesh, &ClassifyParams::default()).unwrap();
    let mut checked = 0;
    for (i, class) in c.triangle_classes.iter().enumerate() {
        let [a, b, d] = mesh.triangle(i);
        let g = Point::new((a.x + b.x + d.x) / 3.0, (a.y + b.y + d.y) / 3.0);
        let want = class.unwrap();
        let region = &c.region(want).region;
        assert!(region.intersects(&g), "triangle {i} ({want:?}) at {g:?}");
        if want == SurfaceClass::Steep {
            assert!(c.steep.region.contains(&g), "triangle {i} at {g:?}");
            checked += 1;
        }
    }
    assert_eq!(checked, 16);
    // Cells over the middle of each wall are steep, over the middle of a floor
    // horizontal.
    let g = &c.grid;
    let at = |x: f64, y: f64| {
        let (i, j) = ((x - g.origin[0]) / g.cell, (y - g.origin[1]) / g.cell);
        g.classes[j as usize * g.nx + i as usize]
    };
    for y in [22.0, 38.0, 59.6, 70.4, 91.5, 98.5, 117.0, 123.0] {
        assert_eq!(at(40.5, y), Some(SurfaceClass::Steep), "y = {y}");
    }
    for y in [8.0, 50.0, 81.0, 108.0, 131.0] {
        assert_eq!(at(40.5, y), Some(SurfaceClass::Horizontal), "y = {y}");
    }
}

#[test]
fn flat_and_gentle_plates_have_no_steep_region() {
    let flat = classify(&plate(30.0, |_, _| 5.0), &ClassifyParams::default()).unwrap();
    assert!(flat.steep.region.0.is_empty() && flat.steep.xy_area == 0.0);
    assert!((flat.horizontal.xy_area - 900.0).abs() < 1e-9);
    assert!(flat.other.region.0.is_empty() && flat.grid.nx == 30);
    // A 20-degree slope is other: no steep, no horizontal.
    let t = deg(20.0).tan();
    let gentle = classify(&plate(30.0, |x, _| x * t), &ClassifyParams::default()).unwrap();
    assert!(gentle.steep.region.0.is_empty() && gentle.horizontal.region.0.is_empty());
    let slope_area = 900.0 / deg(20.0).cos();
    assert!((gentle.other.surface_area - slope_area).abs() < 1e-9);
    // A mesh with nothing to classify is empty, not an error.
    let empty = classify(&TriMesh::default(), &ClassifyParams::default()).unwrap();
    assert_eq!(empty, Classification::default());
    let down = TriMesh::from_triangles(&[[
        Point3::new(0.0, 0.0, 0.0),
        Point3::new(0.0, 1.0, 0.0),
        Point3::new(1.0, 0.0, 0.0),
    ]]);
    let c = classify(&down, &ClassifyParams::default()).unwrap();
    assert_eq!((c.facing_down, c.triangle_classes.clone()), (1, vec![None]));
}

#[test]
fn bad_parameters_name_their_field() {
    let mesh = boss();
    let err = |p: ClassifyParams| classify(&mesh, &p).unwrap_err().to_string();
    let d = ClassifyParams::default();
    let e = err(ClassifyParams {
        steep_angle: deg(5.0),
        ..d
    });
    assert!(
        e.contains("classify.steep_angle") && e.contains("classify.flat_angle"),
        "{e}"
    );
    assert!(e.contains("5 degrees") && e.contains("10 degrees"), "{e}");
    let e = err(ClassifyParams {
        steep_angle: deg(100.0),
        ..d
    });
    assert!(
        e.contains("classify.steep_angle") && e.contains("100 degrees"),
        "{e}"
    );
    let e = err(ClassifyParams {
        flat_angle: -0.1,
        ..d
    });
    assert!(e.starts_with("classify.flat_angle"), "{e}");
    for cell in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = err(ClassifyParams { cell, ..d });
        assert!(
            e.starts_with("classify.cell") && e.contains("above 0"),
            "{e}"
        );
    }
    let e = err(ClassifyParams { cell: 1e-3, ..d });
    assert!(
        e.starts_with("classify.cell") && e.contains(&MAX_CELLS.to_string()),
        "{e}"
    );
}

#[test]
fn the_same_in_one_thread() {
    let mesh = swarf_io::builtin_mesh("fillet-pocket").unwrap();
    let params = ClassifyParams::default();
    let many = classify(&mesh, &params).unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let one = pool.install(|| classify(&mesh, &params)).unwrap();
    assert_eq!(many, one);
    // The pocket: vertical walls and fillet steepest at the wall, floor and top
    // horizontal; the regions tile the block.
    let total = many.steep.xy_area + many.horizontal.xy_area + many.other.xy_area;
    assert!((total - 8000.0).abs() < 1e-3, "{total}");
    println!(
        "fillet-pocket: steep {:.1} ({} cells), horizontal {:.1}, other {:.1}",
        many.steep.xy_area, many.steep.cells, many.horizontal.xy_area, many.other.xy_area
    );
}
