//! Double contacts: the cutter touching the mesh at separated points at once.
//!
//! Thesis 002 §3.1.1 and §5.1.1: where the tool touches two surfaces of a concave edge
//! at the same time, the material between the contacts and the edge is left uncut (a
//! valley); the cleanup tool paths start from these points. A drop whose contacts
//! within [`TOP_TOL`] of the top include two points more than `min_sep` apart is a
//! candidate. Two contacts on one plane are not a valley (a flat end resting on a
//! flat floor touches a whole disc of it): the cutter is convex, so between two points
//! of one supporting plane it lies on that plane. The test that separates the cases
//! is the gap at the XY midpoint `M` of the two contacts: the height of the cutter's
//! lower surface there above the mesh. Zero on a plane, positive over a valley; a gap
//! above `gap_tol` (the machining tolerance: thinner rest material is within
//! tolerance anyway) makes the pair a double contact. Contacts all on one plane are
//! settled without a mesh query.

use crate::plan::DoubleContact;
use swarf_geom::{Point3, TriMesh, Vec3};
use swarf_tool::drop::{DropResult, MeshDropper};

/// Contacts within this of the top height count as simultaneous (mm).
pub const TOP_TOL: f64 = 1e-6;

/// Planes whose unit normals and offsets agree to this are the same (mm, and
/// dimensionless for normals).
const SAME_PLANE: f64 = 1e-9;

/// The double contact at `cl` among `contacts` (all within [`TOP_TOL`] of the top),
/// or `None`.
pub(crate) fn double_contact(
    dropper: &MeshDropper,
    mesh: &TriMesh,
    cl: &Point3,
    contacts: &[DropResult],
    min_sep: f64,
    gap_tol: f64,
) -> Option<DoubleContact> {
    if contacts.len() < 2 || one_plane(mesh, contacts) {
        return None;
    }
    let gap = |a: &Point3, b: &Point3| gap_at(dropper, cl, a, b);
    let mut chosen: Vec<&DropResult> = Vec::new();
    let mut widest = 0.0f64;
    for (i, a) in contacts.iter().enumerate() {
        for b in &contacts[i + 1..] {
            if (a.cc - b.cc).norm() <= min_sep {
                continue;
            }
            let g = gap(&a.cc, &b.cc);
            if g > gap_tol {
                widest = widest.max(g);
                for c in [a, b] {
                    if chosen.iter().all(|q| (q.cc - c.cc).norm() > min_sep) {
                        chosen.push(c);
                    }
                }
            }
        }
    }
    (chosen.len() >= 2).then(|| DoubleContact {
        cl: *cl,
        contacts: chosen.iter().map(|c| c.cc).collect(),
        normals: chosen
            .iter()
            .map(|c| plane(mesh, c).map_or(Vec3::z(), |p| p.0))
            .collect(),
        pass: 0,
        gap: widest,
        ramp: false,
    })
}

/// The gap between the cutter with its tip at `cl` and the mesh at the XY midpoint
/// of `a` and `b`, mm (infinite off the mesh).
fn gap_at(dropper: &MeshDropper, cl: &Point3, a: &Point3, b: &Point3) -> f64 {
    let env = dropper.tool().envelope();
    let (mx, my) = (0.5 * (a.x + b.x), 0.5 * (a.y + b.y));
    let rho = (mx - cl.x).hypot(my - cl.y);
    let cutter = cl.z + env.height(rho.min(env.radius()));
    dropper
        .surface_z(mx, my)
        .map_or(f64::INFINITY, |z| cutter - z)
}

/// The double contact at the foot of a cliff of the CL curve: the cutter at `cl`
/// rests on `low` and, moving along the unit XY direction `dir`, meets a vertical
/// wall at once (the drop height jumps up there). The wall touches the cutter where
/// its profile's normal is horizontal (the ball's equator, a flat end's rim), at
/// `wall`. Kept, as any double contact, when the two points are more than `min_sep`
/// apart and the gap under the cutter between them is above `gap_tol`.
pub(crate) fn cliff_contact(
    dropper: &MeshDropper,
    mesh: &TriMesh,
    cl: &Point3,
    low: &DropResult,
    dir: [f64; 2],
    min_sep: f64,
    gap_tol: f64,
) -> Option<DoubleContact> {
    let side = dropper
        .tool()
        .cutter()
        .profile()
        .contact_for_normal_angle(0.0)?;
    let (rho, z) = (side.point.rho, side.point.z);
    let wall = Point3::new(cl.x + rho * dir[0], cl.y + rho * dir[1], cl.z + z);
    if (wall - low.cc).norm() <= min_sep {
        return None;
    }
    let gap = gap_at(dropper, cl, &low.cc, &wall);
    (gap > gap_tol && gap.is_finite()).then(|| DoubleContact {
        cl: *cl,
        contacts: vec![low.cc, wall],
        normals: vec![
            plane(mesh, low).map_or(Vec3::z(), |p| p.0),
            Vec3::new(-dir[0], -dir[1], 0.0),
        ],
        pass: 0,
        gap,
        ramp: false,
    })
}

/// The plane of a contact's triangle (upward unit normal, offset), `None` for a
/// degenerate triangle.
fn plane(mesh: &TriMesh, c: &DropResult) -> Option<(Vec3, f64)> {
    mesh.normal(c.tri as usize).map(|n| {
        let n: Vec3 = if n.z < 0.0 { -n } else { n };
        (n, n.dot(&c.cc.coords))
    })
}

fn close(a: (Vec3, f64), b: (Vec3, f64)) -> bool {
    (a.0 - b.0).norm() < SAME_PLANE && (a.1 - b.1).abs() < SAME_PLANE
}

/// True when the two contacts' triangles lie in one plane (a degenerate triangle
/// counts as in any plane: it lies on its neighbours' edges).
pub(crate) fn same_plane(mesh: &TriMesh, a: &DropResult, b: &DropResult) -> bool {
    match (plane(mesh, a), plane(mesh, b)) {
        (Some(p), Some(q)) => close(p, q),
        _ => true,
    }
}

/// True when every contact's triangle lies in the first one's plane (degenerate ones
/// aside).
fn one_plane(mesh: &TriMesh, contacts: &[DropResult]) -> bool {
    let Some(p0) = contacts.iter().find_map(|c| plane(mesh, c)) else {
        return true;
    };
    contacts
        .iter()
        .filter_map(|c| plane(mesh, c))
        .all(|p| close(p, p0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_tool::drop::DropScratch;

    fn p(x: f64, y: f64, z: f64) -> Point3 {
        Point3::new(x, y, z)
    }

    /// A V-groove along x: two planes rising at 45 degrees from the line y = 0.
    fn groove() -> TriMesh {
        let s = |y: f64| y.abs();
        let mut soup = Vec::new();
        for (y0, y1) in [(-10.0, 0.0), (0.0, 10.0)] {
            soup.push([p(-20.0, y0, s(y0)), p(20.0, y0, s(y0)), p(20.0, y1, s(y1))]);
            soup.push([p(-20.0, y0, s(y0)), p(20.0, y1, s(y1)), p(-20.0, y1, s(y1))]);
        }
        TriMesh::from_triangles(&soup)
    }

    fn contacts(d: &MeshDropper, x: f64, y: f64) -> (Point3, Vec<DropResult>) {
        let mut c = Vec::new();
        let r = d
            .drop_with_contacts(x, y, TOP_TOL, &mut DropScratch::default(), &mut c)
            .unwrap();
        (p(x, y, r.z), c)
    }

    #[test]
    fn a_ball_in_a_v_groove_touches_both_flanks() {
        let mesh = groove();
        let d = MeshDropper::new(&mesh, &"ball:d=8".parse().unwrap());
        let (cl, c) = contacts(&d, 3.0, 0.0);
        let dc = double_contact(&d, &mesh, &cl, &c, 0.2, 0.01).unwrap();
        assert_eq!(dc.contacts.len(), 2);
        // The ball centre sits R / cos 45 above the groove bottom; the contacts are at
        // y = +-R sin 45.
        let r = 4.0;
        assert!((cl.z - (r * 2f64.sqrt() - r)).abs() < 1e-12);
        for q in &dc.contacts {
            assert!((q.y.abs() - r / 2f64.sqrt()).abs() < 1e-9, "{q:?}");
        }
        // Off the groove's axis the ball touches one flank only.
        let (cl, c) = contacts(&d, 3.0, 2.0);
        assert!(double_contact(&d, &mesh, &cl, &c, 0.2, 0.01).is_none());
    }

    #[test]
    fn a_flat_end_on_a_floor_is_not_a_double_contact() {
        let s = [
            p(0.0, 0.0, 1.0),
            p(10.0, 0.0, 1.0),
            p(10.0, 10.0, 1.0),
            p(0.0, 10.0, 1.0),
        ];
        let mesh = TriMesh::from_triangles(&[[s[0], s[1], s[2]], [s[0], s[2], s[3]]]);
        let d = MeshDropper::new(&mesh, &"flat:d=6".parse().unwrap());
        let (cl, c) = contacts(&d, 5.0, 5.0);
        assert_eq!(c.len(), 2);
        assert!(double_contact(&d, &mesh, &cl, &c, 0.15, 0.01).is_none());
        // A shallow V (slope 0.001): the rim touches both flanks at x = +-3, 0.003 mm
        // above the crease. Within a tolerance of 0.01 that is no valley; with 0.001
        // it is.
        let v = |x: f64, y: f64| p(x, y, 0.001 * x.abs());
        let crease = TriMesh::from_triangles(&[
            [v(0.0, -10.0), v(10.0, -10.0), v(10.0, 10.0)],
            [v(0.0, -10.0), v(10.0, 10.0), v(0.0, 10.0)],
            [v(-10.0, -10.0), v(0.0, -10.0), v(0.0, 10.0)],
            [v(-10.0, -10.0), v(0.0, 10.0), v(-10.0, 10.0)],
        ]);
        let d = MeshDropper::new(&crease, &"flat:d=6".parse().unwrap());
        let (cl, c) = contacts(&d, 0.0, 0.0);
        assert!((cl.z - 0.003).abs() < 1e-12);
        assert!(double_contact(&d, &crease, &cl, &c, 0.15, 0.01).is_none());
        assert!(double_contact(&d, &crease, &cl, &c, 0.15, 0.001).is_some());
    }
}
