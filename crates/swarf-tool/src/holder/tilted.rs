//! Shank and holder against a mesh for a tilted (five-axis) tool, and the smallest
//! extra tilt that clears.
//!
//! In the tool frame `(b1, b2, a)` of a pose's axis `a` ([`crate::pose::reference_frame`])
//! the tool is vertical, so the vertical check ([`super::vertical`]) applies to the
//! mesh expressed in that frame: the clearance is how far the assembly could still
//! move toward the part along its own axis (negative: how far it reaches in). As in
//! three axes the pieces are extended along the axis away from the tip (the spindle
//! above the holder), so anything the tool would meet on its way in along the axis
//! counts. One frame serves every pose with the same axis (3+2 work); a new axis
//! re-lays the mesh's grid ([`Views`] keeps one per axis). Along its own axis a
//! holder piece moves by exactly the change of stick-out, so the shortest stick-out
//! that clears a pose is found in its frame as in three axes, and over a path of
//! any axes it is the largest of the poses' ([`shortest_stick_out_posed`]).
//!
//! The tilt search turns the axis about a point on it `pivot` above the tool tip (the
//! tip itself, or a ball's centre, about which the ball's cut does not change) in
//! the plane of the axis and a given direction, `a(t) = a cos t + d sin t` (`d` the
//! direction's part normal to `a`; the tip moves to `pivot point - pivot a(t)`),
//! steps `t` from 0 by `step` up to `max_tilt`, and bisects between the last
//! step that collides and the first that clears down to `tolerance`. The clearance
//! need not grow steadily with the tilt, so a window of clearing tilts narrower than
//! the step can be missed; the answer is the first clearing tilt on that grid.

use super::Assembly;
use super::vertical::{Clearance, Prepared, StickOut, collisions, shortest_from};
use crate::drop::{DropScratch, MeshDropper};
use crate::error::ToolError;
use crate::pose::{Pose, reference_frame};
use std::collections::HashMap;
use swarf_geom::{Point3, TriMesh, Vec3};

/// How the clearing tilt is searched (radians).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TiltSearch {
    /// Step of the scan, radians.
    pub step: f64,
    /// Largest extra tilt tried, radians.
    pub max_tilt: f64,
    /// Bisection stops when the bracket is this narrow, radians.
    pub tolerance: f64,
    /// How far above the tool tip along the axis the point the axis turns about
    /// lies, mm (0: the tip).
    pub pivot: f64,
}

impl Default for TiltSearch {
    /// 1 degree steps up to 60 degrees, refined to 1e-4 rad, about the tip.
    fn default() -> Self {
        TiltSearch {
            step: 1f64.to_radians(),
            max_tilt: 60f64.to_radians(),
            tolerance: 1e-4,
            pivot: 0.0,
        }
    }
}

/// The outcome of a tilt search.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Tilt {
    /// The pose clears as it is.
    Clear,
    /// Tilting by `tilt` (radians) clears: the new pose and its clearance (mm).
    Clears {
        /// Extra tilt, radians.
        tilt: f64,
        /// The tilted unit axis.
        axis: Vec3,
        /// The tool tip there (moved when the search turns about a point above it).
        cl: Point3,
        /// Clearance there, mm (>= 0).
        clearance: f64,
    },
    /// No tilt up to the search's maximum clears (or the direction is along the axis).
    Fails,
}

/// A mesh re-laid in the frame of one tool axis.
pub struct AxisView {
    frame: [Vec3; 3],
    dropper: MeshDropper,
}

impl AxisView {
    /// The mesh seen along `axis` (unit or not); `None` for a zero or non-finite
    /// axis.
    pub fn new(mesh: &TriMesh, axis: &Vec3, assembly: &Assembly) -> Option<AxisView> {
        let a = Pose::new(Point3::origin(), *axis)?.axis;
        let (b1, b2) = reference_frame(&a);
        let frame = [b1, b2, a];
        let local = TriMesh {
            vertices: mesh.vertices.iter().map(|p| to_frame(&frame, p)).collect(),
            triangles: mesh.triangles.clone(),
        };
        Some(AxisView {
            frame,
            dropper: MeshDropper::new(&local, &assembly.cutter),
        })
    }

    /// The clearance of the shank and holder (at the assembly's stick-out) with the
    /// tool tip at `cl` along this view's axis; `None` when no piece is over the
    /// part.
    ///
    /// # Units
    /// mm.
    ///
    /// # Errors
    /// A shank or holder segment outside the domain of tools.
    pub fn clearance(
        &self,
        assembly: &Assembly,
        cl: &Point3,
    ) -> Result<Option<Clearance>, ToolError> {
        let mut pieces = assembly.shank_pieces(assembly.stick_out)?;
        pieces.extend(assembly.holder_pieces(assembly.stick_out)?);
        Ok(self.clearance_of(&Prepared::new(pieces), cl, &mut DropScratch::default()))
    }

    /// The clearance of `pieces` with the tool tip at `cl`, the contact in the
    /// mesh's own frame.
    fn clearance_of(
        &self,
        pieces: &Prepared,
        cl: &Point3,
        scratch: &mut DropScratch,
    ) -> Option<Clearance> {
        let local = to_frame(&self.frame, cl);
        let mut c = pieces.clearance(&self.dropper, &local, scratch);
        if let Some(c) = &mut c {
            c.contact = from_frame(&self.frame, &c.contact);
        }
        c
    }
}

/// A mesh's views along the tool axes asked for, each laid out once.
pub struct Views<'m> {
    mesh: &'m TriMesh,
    by_axis: HashMap<[u64; 3], Option<AxisView>>,
}

impl<'m> Views<'m> {
    /// No view laid out yet.
    pub fn new(mesh: &'m TriMesh) -> Views<'m> {
        Views {
            mesh,
            by_axis: HashMap::new(),
        }
    }

    /// The view along `axis` ([`AxisView::new`]).
    pub fn along(&mut self, axis: &Vec3, assembly: &Assembly) -> Option<&AxisView> {
        let key = [axis.x, axis.y, axis.z].map(f64::to_bits);
        let mesh = self.mesh;
        self.by_axis
            .entry(key)
            .or_insert_with(|| AxisView::new(mesh, axis, assembly))
            .as_ref()
    }
}

/// The shortest stick-out that clears every one of `poses`, whatever their axes
/// ([`super::vertical`]'s rule in each pose's own frame: the holder's needs at
/// every pose, then the shank bared to the largest): vertical poses
/// ([`Pose::is_vertical`]) on `dropper` (the mesh as it is), the others in their
/// views. Pose indices are into `poses`.
///
/// # Errors
/// A shank or holder segment outside the domain of tools.
pub fn shortest_stick_out_posed(
    assembly: &Assembly,
    dropper: &MeshDropper,
    views: &mut Views<'_>,
    poses: &[Pose],
) -> Result<StickOut, ToolError> {
    let mut scratch = DropScratch::default();
    let mut at = |pieces: &Prepared, pose: &Pose, views: &mut Views<'_>| {
        if pose.is_vertical() {
            pieces.clearance(dropper, &pose.cl, &mut scratch)
        } else {
            views
                .along(&pose.axis, assembly)?
                .clearance_of(pieces, &pose.cl, &mut scratch)
        }
    };
    let face_pieces = Prepared::new(assembly.holder_pieces(0.0)?);
    let face: Vec<Option<Clearance>> = poses.iter().map(|p| at(&face_pieces, p, views)).collect();
    shortest_from(assembly, &face, |shank| {
        let clear: Vec<Option<Clearance>> = poses.iter().map(|p| at(shank, p, views)).collect();
        let cls: Vec<Point3> = poses.iter().map(|p| p.cl).collect();
        Ok(collisions(&cls, &clear).first().copied())
    })
}

fn to_frame(f: &[Vec3; 3], p: &Point3) -> Point3 {
    Point3::new(
        p.coords.dot(&f[0]),
        p.coords.dot(&f[1]),
        p.coords.dot(&f[2]),
    )
}

fn from_frame(f: &[Vec3; 3], p: &Point3) -> Point3 {
    Point3::from(p.x * f[0] + p.y * f[1] + p.z * f[2])
}

/// The clearance of the shank and holder at `pose` (any axis) against `mesh`.
///
/// # Errors
/// A shank or holder segment outside the domain of tools.
pub fn pose_clearance(
    assembly: &Assembly,
    mesh: &TriMesh,
    pose: &Pose,
) -> Result<Option<Clearance>, ToolError> {
    match AxisView::new(mesh, &pose.axis, assembly) {
        Some(view) => view.clearance(assembly, &pose.cl),
        None => Ok(None),
    }
}

/// The smallest extra tilt of `pose` toward `toward`, about the point `search.pivot`
/// above the tool tip, that keeps the shank and holder clear of `mesh` (module doc).
///
/// # Errors
/// A shank or holder segment outside the domain of tools.
pub fn clearing_tilt(
    assembly: &Assembly,
    mesh: &TriMesh,
    pose: &Pose,
    toward: &Vec3,
    search: &TiltSearch,
) -> Result<Tilt, ToolError> {
    let Some(a) = Pose::new(pose.cl, pose.axis).map(|p| p.axis) else {
        return Ok(Tilt::Fails);
    };
    let Some(d) = Pose::new(pose.cl, toward - toward.dot(&a) * a).map(|p| p.axis) else {
        return Ok(Tilt::Fails);
    };
    let centre = pose.cl + search.pivot * a;
    let pose_at = |t: f64| {
        let axis = a * t.cos() + d * t.sin();
        Pose {
            cl: centre - search.pivot * axis,
            axis,
        }
    };
    let clearance = |t: f64| -> Result<f64, ToolError> {
        let c = pose_clearance(assembly, mesh, &pose_at(t))?;
        Ok(c.map_or(f64::INFINITY, |c| c.clearance))
    };
    if clearance(0.0)? >= 0.0 {
        return Ok(Tilt::Clear);
    }
    let step = search.step.max(search.tolerance).max(1e-9);
    let (mut lo, mut hi) = (0.0, None);
    let mut t = step;
    while t <= search.max_tilt + 1e-12 {
        if clearance(t)? >= 0.0 {
            hi = Some(t);
            break;
        }
        lo = t;
        t += step;
    }
    let Some(mut hi) = hi else {
        return Ok(Tilt::Fails);
    };
    while hi - lo > search.tolerance {
        let mid = 0.5 * (lo + hi);
        if clearance(mid)? >= 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let Pose { cl, axis } = pose_at(hi);
    Ok(Tilt::Clears {
        tilt: hi,
        axis,
        cl,
        clearance: clearance(hi)?,
    })
}
