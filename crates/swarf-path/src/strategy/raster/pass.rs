//! One raster pass: drop-cutter along a line, sampled adaptively.
//!
//! The CL curve over a line is the drop height along it. It is sampled every
//! `init_step` (a quarter of the tool radius: a bump of the CL curve is at least as
//! wide as the cutter, the inverted tool shape over a spike, so none falls between
//! samples), then refined: between two samples with contact the midpoint is dropped,
//! and where it is further than the tolerance from their chord it is inserted and both
//! halves are refined, down to `min_step`. Where contact begins or ends between two
//! samples the boundary is bisected to `min_step` the same way, and the pass is split
//! there (the cutter leaves the mesh). This is OpenCAMLib's AdaptivePathDropCutter
//! idea with the test on the actual deviation from the chord rather than on angles.
//!
//! At `min_step` the midpoint may still be off the chord: the CL curve jumps (a flat
//! end over a wall) somewhere in the interval, on either side of the midpoint, or dips
//! into a valley narrower than `min_step`. There the pass climbs vertically at one
//! end to the highest of the three samples, crosses at that height and comes down
//! vertically at the other end (a staircase), so its moves stay above every sample
//! and above a single jump wherever it lies; the CL curve is not followed closer than
//! `min_step` there.
//!
//! Where the contact jumps from one side of a valley to the other between two
//! samples, the crease of the CL curve between them (the point where the cutter
//! touches both sides) is found by bisection and added: the pass goes down to the
//! valley's reachable bottom, and the double contact there is recorded.

use crate::plan::DoubleContact;
use crate::strategy::raster::double::{TOP_TOL, cliff_contact, double_contact, same_plane};
use crate::strategy::raster::{DOUBLE_SEPARATION_RADII, INIT_STEP_RADII, MIN_STEP_FLOOR};
use swarf_geom::{Point3, TriMesh, Vec3};
use swarf_tool::Pose;
use swarf_tool::drop::{DropResult, DropScratch, MeshDropper};
use swarf_toolpath::{Contact, PathPoint};

/// The crease between two contacts is located to this along the pass, mm.
pub const SWITCH_TOL: f64 = 1e-8;
/// Distance along the line that gives the direction of a cliff, mm.
const CLIFF_PROBE: f64 = 1e-3;
/// Most bisection steps of a crease search.
const SWITCH_STEPS: usize = 48;
/// A contact that moves more than this many times as far as the tool between two
/// samples has jumped (on a smooth convex surface it moves less than the tool, on a
/// concave one of radius above 4/3 of the tool's less than 4 times as far).
pub const JUMP_RATIO: f64 = 4.0;

/// Sampling parameters of a pass.
pub(crate) struct Sampler<'a> {
    /// The mesh, for contact normals.
    pub mesh: &'a TriMesh,
    /// The prepared mesh and cutter.
    pub dropper: &'a MeshDropper,
    /// Largest deviation of the CL polyline from the CL curve at a midpoint, mm.
    pub tolerance: f64,
    /// First sampling step, mm.
    pub init_step: f64,
    /// Smallest step of the refinement, mm.
    pub min_step: f64,
    /// Contacts further apart than this can make a double contact, mm.
    pub min_sep: f64,
    /// Refine between samples to the tolerance (a tool path); without it only the
    /// creases are searched (a contact scan).
    pub refine: bool,
}

/// A sample of the line: parameter, drop height (`None` off the mesh), contact.
#[derive(Debug, Clone, Copy)]
struct Sample {
    t: f64,
    hit: Option<DropResult>,
    /// A staircase corner: the height of a move, not a drop.
    corner: Option<f64>,
}

/// What a pass produced: its pieces (split where contact ends) and double contacts.
#[derive(Debug, Default)]
pub(crate) struct PassOut {
    /// Pieces in travel order (+t).
    pub pieces: Vec<Vec<PathPoint>>,
    /// Double contacts found at the samples.
    pub doubles: Vec<DoubleContact>,
}

/// A curve in XY to drop the cutter along: its point at a parameter, and the
/// parameters it must be sampled at (its ends and corners, ascending).
pub(crate) trait Along {
    /// The point at parameter `t`.
    fn at(&self, t: f64) -> [f64; 2];
    /// The parameters of the ends and corners, ascending.
    fn breaks(&self) -> Vec<f64>;
}

/// A line `origin + t dir`, `t` in `[t0, t1]`.
pub(crate) struct Line {
    pub origin: [f64; 2],
    pub dir: [f64; 2],
    pub t0: f64,
    pub t1: f64,
}

impl Along for Line {
    fn at(&self, t: f64) -> [f64; 2] {
        [
            self.origin[0] + t * self.dir[0],
            self.origin[1] + t * self.dir[1],
        ]
    }

    fn breaks(&self) -> Vec<f64> {
        vec![self.t0, self.t1]
    }
}

impl<'a> Sampler<'a> {
    /// The sampler of [`crate::strategy::raster`]: first step [`INIT_STEP_RADII`] tool radii,
    /// refinement down to the tolerance (not below [`MIN_STEP_FLOOR`]), double
    /// contacts at [`DOUBLE_SEPARATION_RADII`] tool radii.
    pub(crate) fn new(
        mesh: &'a TriMesh,
        dropper: &'a MeshDropper,
        tolerance: f64,
        refine: bool,
    ) -> Sampler<'a> {
        let radius = dropper.tool().radius();
        let init_step = INIT_STEP_RADII * radius;
        Sampler {
            mesh,
            dropper,
            tolerance,
            init_step,
            min_step: tolerance.max(MIN_STEP_FLOOR).min(0.5 * init_step),
            min_sep: DOUBLE_SEPARATION_RADII * radius,
            refine,
        }
    }

    /// Samples `line` (module doc): every piece between breaks evenly at most
    /// `init_step` apart, then refined.
    pub(crate) fn run(&self, line: &impl Along, scratch: &mut DropScratch) -> PassOut {
        let mut out = PassOut::default();
        let breaks = line.breaks();
        let mut ts = Vec::new();
        for w in breaks.windows(2) {
            let span = w[1] - w[0];
            if span.is_nan() || span < 0.0 {
                return out;
            }
            let n = (span / self.init_step).ceil().max(1.0) as usize;
            ts.extend((0..n).map(|i| w[0] + span * i as f64 / n as f64));
        }
        let Some(&last) = breaks.last() else {
            return out;
        };
        ts.push(last);
        let mut contacts = Vec::new();
        let mut drop = |t: f64, check: bool| {
            self.sample(line, t, check, scratch, &mut contacts, &mut out.doubles)
        };
        let first: Vec<Sample> = ts.into_iter().map(|t| drop(t, true)).collect();
        let mut samples = vec![first[0]];
        for w in first.windows(2) {
            if self.refine {
                self.refine(w[0], w[1], &mut drop, &mut samples);
            }
            samples.push(w[1]);
        }
        let (switches, cliffs) = self.switches(line, &samples, &mut drop);
        if !switches.is_empty() {
            samples.extend(switches);
            samples.sort_by(|a, b| a.t.total_cmp(&b.t));
        }
        out.doubles.extend(cliffs);
        out.pieces = self.pieces(line, &samples);
        out
    }

    /// Drops at `t`; with `check`, records a double contact there if any.
    fn sample(
        &self,
        line: &impl Along,
        t: f64,
        check: bool,
        scratch: &mut DropScratch,
        contacts: &mut Vec<DropResult>,
        doubles: &mut Vec<DoubleContact>,
    ) -> Sample {
        let [x, y] = line.at(t);
        if !check {
            let hit = self.dropper.drop(x, y, scratch);
            return Sample {
                t,
                hit,
                corner: None,
            };
        }
        let hit = self
            .dropper
            .drop_with_contacts(x, y, TOP_TOL, scratch, contacts);
        if let Some(h) = hit
            && contacts.len() > 1
        {
            let cl = Point3::new(x, y, h.z);
            let tol = self.tolerance;
            doubles.extend(double_contact(
                self.dropper,
                self.mesh,
                &cl,
                contacts,
                self.min_sep,
                tol,
            ));
        }
        Sample {
            t,
            hit,
            corner: None,
        }
    }

    /// Pushes the samples strictly between `a` and `b` that the refinement inserts.
    fn refine(
        &self,
        a: Sample,
        b: Sample,
        drop: &mut impl FnMut(f64, bool) -> Sample,
        out: &mut Vec<Sample>,
    ) {
        if a.hit.is_none() && b.hit.is_none() {
            return;
        }
        let m = drop(0.5 * (a.t + b.t), true);
        let coarse = 0.5 * (b.t - a.t) >= self.min_step;
        match (a.hit, m.hit, b.hit) {
            (Some(ha), Some(hm), Some(hb)) => {
                let dev = hm.z - 0.5 * (ha.z + hb.z);
                if dev.abs() <= self.tolerance {
                    return;
                }
                if coarse {
                    self.refine(a, m, drop, out);
                    out.push(m);
                    self.refine(m, b, drop, out);
                } else {
                    staircase(a.t, ha.z, hm.z, b.t, hb.z, out);
                }
            }
            _ if coarse => {
                self.refine(a, m, drop, out);
                out.push(m);
                self.refine(m, b, drop, out);
            }
            _ => {}
        }
    }

    /// The creases of the CL curve: where the winning contact jumps between
    /// neighbouring samples, by more than `min_sep` and more than [`JUMP_RATIO`] times
    /// the tool's move, from one plane to another, the cutter passes over a valley and
    /// touches both sides at one point between them. That point is bisected to
    /// [`SWITCH_TOL`] (the two contacts' heights there then differ by far less than
    /// the double-contact tolerance) and returned as a sample; the drop there records
    /// the double contact when there is one. Consecutive drops of a pass rarely land
    /// exactly on such a crease, so without this step a raster crossing a valley
    /// would record none. Where the heights at the two ends of the final bracket
    /// still differ by more than the tolerance, the CL curve has a cliff there (a
    /// vertical wall): the cutter at its foot touches the floor and the wall at once,
    /// and that double contact is returned beside the samples
    /// (`raster_double::cliff_contact`).
    fn switches(
        &self,
        line: &impl Along,
        samples: &[Sample],
        drop: &mut impl FnMut(f64, bool) -> Sample,
    ) -> (Vec<Sample>, Vec<DoubleContact>) {
        let mut out = Vec::new();
        let mut cliffs = Vec::new();
        for w in samples.windows(2) {
            let (Some(ha), Some(hb)) = (w[0].hit, w[1].hit) else {
                continue;
            };
            let jump = (ha.cc - hb.cc).norm();
            let moved = w[1].t - w[0].t;
            if jump <= self.min_sep.max(JUMP_RATIO * moved) || same_plane(self.mesh, &ha, &hb) {
                continue;
            }
            let (mut a, mut b) = ((w[0].t, ha), (w[1].t, hb));
            for _ in 0..SWITCH_STEPS {
                if b.0 - a.0 <= SWITCH_TOL {
                    break;
                }
                let m = drop(0.5 * (a.0 + b.0), false);
                let Some(h) = m.hit else {
                    break;
                };
                if (h.cc - a.1.cc).norm() <= (h.cc - b.1.cc).norm() {
                    a = (m.t, h);
                } else {
                    b = (m.t, h);
                }
            }
            if (a.1.z - b.1.z).abs() > self.tolerance {
                cliffs.extend(self.cliff(line, a, b));
                continue;
            }
            let m = drop(0.5 * (a.0 + b.0), true);
            if m.hit.is_some() {
                out.push(m);
            }
        }
        (out, cliffs)
    }

    /// The double contact at the foot of the cliff between the bracket ends `a` and
    /// `b` (parameter, drop).
    fn cliff(
        &self,
        line: &impl Along,
        a: (f64, DropResult),
        b: (f64, DropResult),
    ) -> Option<DoubleContact> {
        let (low, high) = if a.1.z < b.1.z { (a, b) } else { (b, a) };
        let step = (high.0 - low.0).signum() * CLIFF_PROBE;
        let (p, q) = (line.at(low.0), line.at(low.0 + step));
        let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
        let len = dx.hypot(dy);
        if len.is_nan() || len <= 0.0 {
            return None;
        }
        let cl = Point3::new(p[0], p[1], low.1.z);
        cliff_contact(
            self.dropper,
            self.mesh,
            &cl,
            &low.1,
            [dx / len, dy / len],
            self.min_sep,
            self.tolerance,
        )
    }

    /// The runs of samples with contact as pieces of path points.
    fn pieces(&self, line: &impl Along, samples: &[Sample]) -> Vec<Vec<PathPoint>> {
        let mut pieces = Vec::new();
        let mut cur: Vec<PathPoint> = Vec::new();
        for s in samples {
            let [x, y] = line.at(s.t);
            match (s.corner, s.hit) {
                (Some(z), _) => cur.push(PathPoint::new(Pose::vertical(Point3::new(x, y, z)))),
                (None, Some(h)) => cur.push(self.point(x, y, &h)),
                (None, None) => {
                    if cur.len() > 1 {
                        pieces.push(std::mem::take(&mut cur));
                    }
                    cur.clear();
                }
            }
        }
        if cur.len() > 1 {
            pieces.push(cur);
        }
        pieces
    }

    /// The path point of a drop: CL on the axis, contact on the touched triangle
    /// (its upward normal; uv NaN on a mesh).
    fn point(&self, x: f64, y: f64, h: &DropResult) -> PathPoint {
        drop_point(self.mesh, [x, y], h.z, h)
    }
}

/// Corners taking the path from `(ta, za)` up to the highest of the three heights,
/// across, and down to `(tb, zb)`.
fn staircase(ta: f64, za: f64, zm: f64, tb: f64, zb: f64, out: &mut Vec<Sample>) {
    let top = za.max(zm).max(zb);
    for (t, z) in [(ta, za), (tb, zb)] {
        if top > z {
            out.push(Sample {
                t,
                hit: None,
                corner: Some(top),
            });
        }
    }
}

/// The path point with its tip at `(xy, z)` and the contact of drop `h` (face = its
/// triangle, normal = the triangle's upward normal, `uv` NaN).
pub(crate) fn drop_point(mesh: &TriMesh, xy: [f64; 2], z: f64, h: &DropResult) -> PathPoint {
    let normal = mesh
        .normal(h.tri as usize)
        .map_or(Vec3::z(), |n| if n.z < 0.0 { -n } else { n });
    PathPoint {
        pose: Pose::vertical(Point3::new(xy[0], xy[1], z)),
        contact: Some(Contact {
            point: h.cc,
            normal,
            face: h.tri as usize,
            uv: [f64::NAN, f64::NAN],
        }),
        lifted: 0.0,
    }
}
