//! The report pictures of a real verification: a ball raster over a flat part with
//! one planted gouge (one gouge region), titled with a title longer than the canvas.
//! Text that ran off the canvas would leave ink in its outer band; the layout's own
//! tests (swarf_report::page) check that no two labels overlap.

mod common;

use std::io::Cursor;
use swarf_geom::{Part, Patch, Point3};
use swarf_report::picture::{deviation_png, toolpath_png};
use swarf_sim::report::{ReportContext, text_summary};
use swarf_sim::{Design, Quiet, StockSpec, Verification, VerifyOptions, verify};
use swarf_tool::Cutter;
use swarf_toolpath::{MotionKind, Program};

/// Width of the canvas band that must stay white, px.
const BAND: usize = 4;

const TITLE: &str = "normal deviation: a-program-with-a-long-name.cl, \
    apt:d=38.1,r=6.35,e=12.700000000000001,f=0,alpha=0,beta=0,h=25.4, tol 0.01 mm";

/// Rasters along x over [0, 40] x [0, 20] at z = 0, one point pushed 0.05 mm down.
fn program() -> Program {
    let mut program = Program::new("raster");
    let mut at = [0.0, 0.0, 5.0];
    for k in 0..14 {
        let y = 1.5 * k as f64;
        let mut points = vec![([-4.0, y, 5.0], MotionKind::Rapid)];
        for s in 0..=22 {
            let z = if k == 6 && s == 12 { -0.05 } else { 0.0 };
            points.push(([-4.0 + 2.0 * s as f64, y, z], MotionKind::Linear));
        }
        points.push(([40.0, y, 5.0], MotionKind::Rapid));
        common::chain(&mut program, &mut at, points);
    }
    program
}

fn verification() -> (Verification, Program) {
    let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
    let corners = vec![p(0.0, 0.0), p(0.0, 20.0), p(40.0, 0.0), p(40.0, 20.0)];
    let part = Part::new("plane", vec![Patch::bezier([1, 1], corners).unwrap()]);
    let cutter: Cutter = "ball:d=6".parse().unwrap();
    let opts = VerifyOptions {
        cell: Some(0.125),
        stock: StockSpec::Offset { allowance: 0.5 },
        ..VerifyOptions::default()
    };
    let program = program();
    let v = verify(Design::Part(&part), &program, &cutter, &opts, &Quiet).unwrap();
    (v, program)
}

/// Width, height and RGB bytes of a PNG.
fn decode(png: &[u8]) -> (usize, usize, Vec<u8>) {
    let mut reader = png::Decoder::new(Cursor::new(png)).read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    (info.width as usize, info.height as usize, buf)
}

/// Pixels in the outer band that are not white.
fn ink_in_band(png: &[u8]) -> usize {
    let (w, h, rgb) = decode(png);
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .filter(|&(x, y)| x < BAND || y < BAND || x + BAND >= w || y + BAND >= h)
        .filter(|&(x, y)| rgb[3 * (y * w + x)..3 * (y * w + x) + 3] != [255; 3])
        .count()
}

#[test]
fn long_titles_stay_on_the_canvas_and_pictures_repeat_byte_for_byte() {
    let (v, program) = verification();
    assert_eq!(v.deviation.summary.gouge.regions, 1);
    let dev = deviation_png(&v, TITLE).unwrap();
    let path = toolpath_png(&v, &program.motions, TITLE).unwrap();
    assert_eq!(ink_in_band(&dev), 0);
    assert_eq!(ink_in_band(&path), 0);
    assert_eq!(dev, deviation_png(&v, TITLE).unwrap());
    assert_eq!(path, toolpath_png(&v, &program.motions, TITLE).unwrap());
    let ctx = ReportContext {
        part: "plane".into(),
        program: "raster".into(),
        tool: "ball:d=6".into(),
        stock: "design + 0.5 mm".into(),
        warnings: Vec::new(),
        stopped: None,
    };
    let text = text_summary(&v, &ctx);
    assert!(text.contains(" in 1 region, deepest"), "{text}");
}
