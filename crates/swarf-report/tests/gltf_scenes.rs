//! The GLB scenes read back with an independent reader (the `gltf` crate): node
//! names, primitive modes and counts, stock colours against the heat map's scale,
//! the stated decimation error against a brute-force one, the cutter at a tilted
//! pose, and byte-identical repeats.

mod common;

use swarf_geom::{Part, Patch, Point3, Vec3};
use swarf_report::gltf::{StockMeshOptions, cutter_glb, part_glb, stock_glb, toolpath_glb};
use swarf_report::picture::limits;
use swarf_sim::{Design, Quiet, StockSpec, Verification, VerifyOptions, verify};
use swarf_tool::{Cutter, Pose};
use swarf_toolpath::{MotionKind, Program};

/// A ball-tip raster along x over [0, 40] x [0, 20] on the dome ([`dome`]), stepover 1.5,
/// each pass plunged (a link) and left by rapids, one point pushed 0.05 mm down.
fn program() -> Program {
    let mut program = Program::new("raster");
    let mut at = [0.0, 0.0, 10.0];
    let z = dome;
    for k in 0..14 {
        let y = 1.5 * k as f64;
        let mut points = vec![
            ([-4.0, y, 10.0], MotionKind::Rapid),
            ([-4.0, y, z(0.0, y)], MotionKind::Linear),
        ];
        for s in 0..=22 {
            let x = -4.0 + 2.0 * s as f64;
            let dz = if k == 6 && s == 12 { -0.05 } else { 0.0 };
            points.push(([x, y, z(x.clamp(0.0, 40.0), y) + dz], MotionKind::Linear));
        }
        points.push(([40.0, y, 10.0], MotionKind::Rapid));
        common::chain(&mut program, &mut at, points);
    }
    program
}

/// Height of the dome ([`part`]: a biquadratic Bezier patch over [0, 40] x [0, 20]
/// whose middle control point is 3 mm up) at (x, y): 3 (2u(1-u)) (2v(1-v)).
fn dome(x: f64, y: f64) -> f64 {
    let (u, v) = (x / 40.0, y / 20.0);
    12.0 * u * (1.0 - u) * v * (1.0 - v)
}

fn part() -> Part {
    let mut net = Vec::new();
    for i in 0..3 {
        for j in 0..3 {
            let z = if i == 1 && j == 1 { 3.0 } else { 0.0 };
            net.push(Point3::new(20.0 * i as f64, 10.0 * j as f64, z));
        }
    }
    Part::new("dome", vec![Patch::bezier([2, 2], net).unwrap()])
}

fn verification() -> (Verification, Program, Cutter) {
    let part = part();
    let cutter: Cutter = "ball:d=6".parse().unwrap();
    let opts = VerifyOptions {
        cell: Some(0.125),
        stock: StockSpec::Offset { allowance: 0.5 },
        ..VerifyOptions::default()
    };
    let program = program();
    let v = verify(Design::Part(&part), &program, &cutter, &opts, &Quiet).unwrap();
    (v, program, cutter)
}

/// Node names of a GLB, in order.
fn names(doc: &gltf::Document) -> Vec<String> {
    doc.nodes()
        .map(|n| n.name().unwrap_or("").to_string())
        .collect()
}

/// The first primitive of the node named `name`.
fn primitive<'a>(doc: &'a gltf::Document, name: &str) -> gltf::Primitive<'a> {
    let node = doc.nodes().find(|n| n.name() == Some(name)).unwrap();
    node.mesh().unwrap().primitives().next().unwrap()
}

fn floats(g: &gltf::Gltf, p: &gltf::Primitive<'_>, semantic: &str) -> Vec<f32> {
    let blob = g.blob.as_deref().unwrap();
    let (_, acc) = p
        .attributes()
        .find(|(s, _)| s.to_string() == semantic)
        .unwrap_or_else(|| panic!("no {semantic}"));
    let view = acc.view().unwrap();
    let start = view.offset() + acc.offset();
    let n = acc.count() * acc.dimensions().multiplicity();
    (0..n)
        .map(|k| f32::from_le_bytes(blob[start + 4 * k..start + 4 * k + 4].try_into().unwrap()))
        .collect()
}

fn indices(g: &gltf::Gltf, p: &gltf::Primitive<'_>) -> Vec<u32> {
    let reader = p.reader(|_| g.blob.as_deref());
    reader.read_indices().unwrap().into_u32().collect()
}

#[test]
fn toolpath_has_named_line_sets() {
    let (_, program, cutter) = verification();
    let bytes = toolpath_glb(&program.motions, &cutter).unwrap();
    let g = gltf::Gltf::from_slice(&bytes).unwrap();
    assert_eq!(names(&g.document), ["cuts", "links", "rapids"]);
    let count = |name: &str| {
        let p = primitive(&g.document, name);
        assert_eq!(p.mode(), gltf::mesh::Mode::Lines, "{name}");
        floats(&g, &p, "POSITION").len() / 3
    };
    assert_eq!(count("rapids"), 2 * 28);
    assert_eq!(count("links"), 2 * 14);
    assert_eq!(count("cuts"), 2 * 14 * 23);
    assert_eq!(bytes, toolpath_glb(&program.motions, &cutter).unwrap());
}

#[test]
fn stock_colours_are_the_heat_map_s() {
    let (v, _, _) = verification();
    let (bytes, mesh) = stock_glb(&v, &StockMeshOptions::default()).unwrap();
    assert_eq!(mesh.stride, 1);
    assert_eq!(mesh.height_error, 0.0);
    let g = gltf::Gltf::from_slice(&bytes).unwrap();
    assert_eq!(names(&g.document), ["stock"]);
    let p = primitive(&g.document, "stock");
    assert_eq!(p.mode(), gltf::mesh::Mode::Triangles);
    let (pos, colour) = (floats(&g, &p, "POSITION"), floats(&g, &p, "COLOR_0"));
    let (dev, cell, line) = (
        floats(&g, &p, "_DEVIATION"),
        floats(&g, &p, "_CELL"),
        floats(&g, &p, "_LINE"),
    );
    assert_eq!(pos.len() / 3, mesh.vertices);
    assert_eq!(indices(&g, &p).len() / 3, mesh.triangles);
    let scale = limits(&v);
    let mut gouged = 0;
    for k in 0..mesh.vertices {
        let (i, j) = (cell[2 * k] as usize, cell[2 * k + 1] as usize);
        let c = j * v.grid.nx + i;
        assert_eq!(pos[3 * k + 2], v.stock.heights()[c] as f32);
        let d = v.deviation.values[c];
        let want = scale.colour(d, v.design.heights[c].is_finite());
        let got = [0, 1, 2].map(|n| swarf_report::gltf::glb::srgb(colour[3 * k + n]));
        assert_eq!(got, want, "vertex {k}, cell {i},{j}, deviation {d}");
        if d.is_finite() {
            assert_eq!(dev[k], d as f32);
        }
        gouged += usize::from(d < -v.deviation.summary.tol);
        let m = v.stock.last_motion()[c];
        if m != u32::MAX {
            assert_eq!(line[k] as usize, v.lines[m as usize]);
        }
    }
    assert!(gouged > 0, "the planted gouge shows");
    assert_eq!(
        bytes,
        stock_glb(&v, &StockMeshOptions::default()).unwrap().0
    );
}

/// Brute force: the mesh's height above every cell centre, by testing the cell
/// against every triangle; the largest difference from the cell's height.
fn brute_force_error(v: &Verification, pos: &[f32], idx: &[u32]) -> f64 {
    let mut worst = 0.0f64;
    for j in 0..v.grid.ny {
        for i in 0..v.grid.nx {
            let z = v.stock.heights()[j * v.grid.nx + i];
            let [x, y] = v.grid.centre(i, j);
            let found = idx.chunks_exact(3).find_map(|t| {
                let p: [[f64; 3]; 3] = std::array::from_fn(|n| t[n])
                    .map(|k: u32| [0, 1, 2].map(|c| f64::from(pos[3 * k as usize + c])));
                let d = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1])
                    - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
                let l1 =
                    ((x - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (y - p[0][1])) / d;
                let l2 =
                    ((p[1][0] - p[0][0]) * (y - p[0][1]) - (x - p[0][0]) * (p[1][1] - p[0][1])) / d;
                let inside = l1 >= -1e-4 && l2 >= -1e-4 && l1 + l2 <= 1.0 + 1e-4;
                inside.then(|| p[0][2] + l1 * (p[1][2] - p[0][2]) + l2 * (p[2][2] - p[0][2]))
            });
            if let Some(zm) = found {
                worst = worst.max((zm - z).abs());
            }
        }
    }
    worst
}

#[test]
fn decimated_stock_states_its_error() {
    let (v, _, _) = verification();
    let opts = StockMeshOptions { max_vertices: 4000 };
    let (bytes, mesh) = stock_glb(&v, &opts).unwrap();
    assert!(mesh.stride > 1 && mesh.vertices <= 4000, "{mesh:?}");
    let g = gltf::Gltf::from_slice(&bytes).unwrap();
    let p = primitive(&g.document, "stock");
    let brute = brute_force_error(&v, &floats(&g, &p, "POSITION"), &indices(&g, &p));
    // f32 positions: a few micrometres of rounding either way.
    assert!(
        brute <= mesh.height_error + 1e-4,
        "brute force {brute} > stated {}",
        mesh.height_error
    );
    assert!(
        mesh.height_error <= brute + 1e-4,
        "stated {} > brute force {brute}",
        mesh.height_error
    );
    assert!(mesh.height_error > 0.0);
}

#[test]
fn cutter_at_a_tilted_pose() {
    let cutter: Cutter = "bull:d=38.1,r=6.35,length=25.4".parse().unwrap();
    let axis = Vec3::new(0.3, -0.2, 0.9).normalize();
    let pose = Pose {
        cl: Point3::new(10.0, 20.0, 5.0),
        axis,
    };
    let bytes = cutter_glb(&cutter, &pose).unwrap();
    let g = gltf::Gltf::from_slice(&bytes).unwrap();
    assert_eq!(names(&g.document), ["cutter"]);
    let node = g.document.nodes().next().unwrap();
    let m = node.transform().matrix();
    let p = primitive(&g.document, "cutter");
    let pos = floats(&g, &p, "POSITION");
    let (mut rmax, mut zmax) = (0.0f64, 0.0f64);
    for q in pos.chunks_exact(3) {
        rmax = rmax.max(f64::from(q[0].hypot(q[1])));
        zmax = zmax.max(f64::from(q[2]));
    }
    assert!((rmax - cutter.radius()).abs() < 1e-4 && (zmax - 25.4).abs() < 1e-4);
    // The top of the axis, (0, 0, length) in the tool frame, lands on cl + axis * length.
    let top = [0, 1, 2].map(|r| f64::from(m[2][r]) * 25.4 + f64::from(m[3][r]));
    let want = pose.cl + axis * 25.4;
    for r in 0..3 {
        assert!((top[r] - want[r]).abs() < 1e-4, "{top:?} vs {want:?}");
    }
}

#[test]
fn five_axis_paths_carry_tool_axes() {
    let (_, mut program, cutter) = verification();
    let axis = Vec3::new(0.0, 0.5, 1.0).normalize();
    for m in &mut program.motions {
        m.start.axis = axis;
        m.end.axis = axis;
    }
    let g = gltf::Gltf::from_slice(&toolpath_glb(&program.motions, &cutter).unwrap()).unwrap();
    assert_eq!(names(&g.document), ["cuts", "links", "rapids", "tool axes"]);
    let p = primitive(&g.document, "tool axes");
    let pos = floats(&g, &p, "POSITION");
    assert_eq!(pos.len() / 6, 14 * 23);
    let d = [pos[3] - pos[0], pos[4] - pos[1], pos[5] - pos[2]];
    let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    assert!((f64::from(d[1] / n) - axis.y).abs() < 1e-5);
}

#[test]
fn part_is_its_tessellation() {
    let mesh = part().tessellate(0.01).unwrap();
    let g = gltf::Gltf::from_slice(&part_glb(&mesh).unwrap()).unwrap();
    let p = primitive(&g.document, "part");
    assert_eq!(indices(&g, &p).len(), 3 * mesh.triangles.len());
    assert_eq!(floats(&g, &p, "NORMAL").len(), 3 * mesh.vertices.len());
}
