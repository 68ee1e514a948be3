//! The tool path as line sets: the path of the tool tip (CL points) in three named
//! nodes, `cuts`, `links` and `rapids`, and for five-axis programs the tool axis at
//! each cutting pose as a short line from the CL point (`tool axes`). Every vertex
//! carries the index of its motion in the program (`_MOTION`), so that a viewer can
//! show one operation's path, or the path up to a motion.
//!
//! A program read back from G-code or APT CL does not say which feed moves are
//! links, so they are recognised by their shape: a straight feed move along the tool
//! axis (within 45 degrees of it: a plunge, an approach or a retract) is a link,
//! every other feed move is a cut. Arcs are drawn as [`ARC_CHORDS`] chords each.

use super::glb::{Glb, LINES, linear};
use swarf_toolpath::{Motion, MotionKind};

/// Chords per arc motion.
pub const ARC_CHORDS: usize = 32;
/// At most this many tool axes are drawn (every k-th pose beyond it).
pub const MAX_AXES: usize = 20_000;

/// What a motion is, for drawing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Class {
    /// A feed move that cuts.
    Cut,
    /// A feed move along the tool axis (module doc).
    Link,
    /// A rapid.
    Rapid,
}

impl Class {
    /// The node name of this class.
    pub fn name(self) -> &'static str {
        match self {
            Class::Cut => "cuts",
            Class::Link => "links",
            Class::Rapid => "rapids",
        }
    }

    /// One letter for the viewer's JSON: `c`, `l` or `r`.
    pub fn letter(self) -> char {
        match self {
            Class::Cut => 'c',
            Class::Link => 'l',
            Class::Rapid => 'r',
        }
    }
}

/// The class of `m` (module doc).
pub fn classify(m: &Motion) -> Class {
    match m.kind {
        MotionKind::Rapid => Class::Rapid,
        MotionKind::Arc { .. } => Class::Cut,
        MotionKind::Linear => {
            let d = m.end.cl - m.start.cl;
            let along = d.dot(&m.start.axis).abs();
            if d.norm() > 0.0 && along >= std::f64::consts::FRAC_1_SQRT_2 * d.norm() {
                Class::Link
            } else {
                Class::Cut
            }
        }
    }
}

/// Whether any pose of `motions` has a tool axis other than +z (by the kernel's
/// parallel tolerance, as the simulator decides which motions are upright).
pub fn is_five_axis(motions: &[Motion]) -> bool {
    let tilted = |a: &swarf_geom::Vec3| a.z < 1.0 - swarf_geom::tol::PARALLEL_COS;
    motions
        .iter()
        .any(|m| tilted(&m.start.axis) || tilted(&m.end.axis))
}

/// Line segments (pairs of points, f32 mm) and the motion index of each point.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Segments {
    /// x y z of each point, two points a segment.
    pub points: Vec<f32>,
    /// The index in the program of the motion each point belongs to.
    pub motion: Vec<f32>,
}

impl Segments {
    fn push(&mut self, a: swarf_geom::Point3, b: swarf_geom::Point3, motion: usize) {
        self.points
            .extend([a.x, a.y, a.z, b.x, b.y, b.z].map(|x| x as f32));
        self.motion.extend([motion as f32; 2]);
    }
}

/// The line segments of the motions of `class`.
pub fn segments(motions: &[Motion], class: Class) -> Segments {
    let mut out = Segments::default();
    for (k, m) in motions.iter().enumerate() {
        if classify(m) != class {
            continue;
        }
        match m.kind {
            MotionKind::Arc { .. } => {
                for c in 0..ARC_CHORDS {
                    let t = |c: usize| c as f64 / ARC_CHORDS as f64;
                    out.push(m.point_at(t(c)).cl, m.point_at(t(c + 1)).cl, k);
                }
            }
            _ => out.push(m.start.cl, m.end.cl, k),
        }
    }
    out
}

/// The tool axis at the end of every cutting motion (every k-th beyond
/// [`MAX_AXES`]), `length` mm long, as line segments.
pub fn axis_segments(motions: &[Motion], length: f64) -> Segments {
    let cuts: Vec<(usize, &Motion)> = motions
        .iter()
        .enumerate()
        .filter(|(_, m)| classify(m) == Class::Cut)
        .collect();
    let step = cuts.len().div_ceil(MAX_AXES).max(1);
    let mut out = Segments::default();
    for &(k, m) in cuts.iter().step_by(step) {
        out.push(m.end.cl, m.end.cl + m.end.axis * length, k);
    }
    out
}

/// Colours of the line sets (sRGB): cuts, links, rapids, tool axes; clear of the
/// stock's deviation scale (blue material left, red gouges), as the viewer page
/// draws them.
const COLOURS: [(&str, [u8; 3]); 4] = [
    ("cuts", [45, 45, 50]),
    ("links", [30, 150, 70]),
    ("rapids", [235, 130, 20]),
    ("tool axes", [150, 110, 170]),
];

/// Adds the program's nodes to `glb`: `cuts`, `links`, `rapids` (each present, empty
/// sets as nodes without a mesh) and, for a five-axis program, `tool axes` of
/// `axis_length` mm.
///
/// # Units
/// mm.
pub fn add_toolpath(glb: &mut Glb, motions: &[Motion], axis_length: f64) {
    let mut sets: Vec<(&str, Segments)> = [Class::Cut, Class::Link, Class::Rapid]
        .into_iter()
        .map(|c| (c.name(), segments(motions, c)))
        .collect();
    if is_five_axis(motions) {
        sets.push(("tool axes", axis_segments(motions, axis_length)));
    }
    for (name, data) in sets {
        let colour = COLOURS.iter().find(|c| c.0 == name).map_or([0; 3], |c| c.1);
        if data.points.is_empty() {
            glb.empty_node(name);
            continue;
        }
        let p = glb.floats(&data.points, "VEC3", 3);
        let m = glb.floats(&data.motion, "SCALAR", 1);
        let [r, g, b] = colour.map(linear);
        let mat = glb.material(name, [r, g, b, 1.0], 0.0);
        glb.mesh_node(name, &[("POSITION", p), ("_MOTION", m)], None, LINES, mat);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_geom::Point3;
    use swarf_tool::Pose;

    fn motion(kind: MotionKind, a: [f64; 3], b: [f64; 3]) -> Motion {
        Motion {
            kind,
            start: Pose::vertical(Point3::from(a)),
            end: Pose::vertical(Point3::from(b)),
            feed: 100.0,
            line: 1,
        }
    }

    #[test]
    fn every_point_carries_its_motion() {
        let motions = [
            motion(MotionKind::Rapid, [0.0, 0.0, 10.0], [1.0, 0.0, 10.0]),
            motion(MotionKind::Linear, [1.0, 0.0, 10.0], [1.0, 0.0, 0.0]),
            motion(MotionKind::Linear, [1.0, 0.0, 0.0], [5.0, 0.0, 0.0]),
            motion(MotionKind::Linear, [5.0, 0.0, 0.0], [5.0, 3.0, 0.0]),
        ];
        let cuts = segments(&motions, Class::Cut);
        assert_eq!(cuts.points.len(), 12);
        assert_eq!(cuts.motion, vec![2.0, 2.0, 3.0, 3.0]);
        assert_eq!(segments(&motions, Class::Link).motion, vec![1.0, 1.0]);
        assert_eq!(segments(&motions, Class::Rapid).motion, vec![0.0, 0.0]);
    }
}
