//! The cutter as a mesh: its profile ([`swarf_tool::Cutter::profile`], the meridian
//! half-plane from the tip up) revolved about the tool axis and closed by the disc at
//! the top of the flutes. The mesh is in the tool frame (tip at the origin, axis
//! +z); a pose places it by the node's translation (the CL point) and rotation (the
//! shortest turn of +z onto the tool axis).
//!
//! Arcs of the profile are divided so that no chord strays more than [`CHORD`] from
//! the arc; the revolution has [`SLICES`] slices.

use super::glb::{Glb, TRIANGLES, linear};
use serde_json::json;
use swarf_tool::{Cutter, Pose, RhoZ, Segment};

/// Largest chord error of the profile's arcs, mm.
pub const CHORD: f64 = 0.02;
/// Slices of the revolution.
pub const SLICES: usize = 48;
/// The cutter's colour (sRGB).
const STEEL: [u8; 3] = [200, 170, 60];

/// The profile's points from the tip up, ending on the axis at the top.
pub fn profile_points(cutter: &Cutter) -> Vec<RhoZ> {
    let profile = cutter.profile();
    let mut pts = vec![
        profile
            .segments()
            .first()
            .map_or(RhoZ::default(), Segment::start),
    ];
    for seg in profile.segments() {
        let n = match seg {
            Segment::Line { .. } => 1,
            Segment::Arc { radius, .. } => {
                let step = 2.0 * (2.0 * radius * CHORD).sqrt().min(*radius);
                ((seg.length() / step).ceil() as usize).clamp(1, 64)
            }
        };
        for k in 1..=n {
            pts.push(seg.point_at(seg.length() * k as f64 / n as f64).0);
        }
    }
    pts.push(RhoZ::new(0.0, profile.length()));
    pts.dedup_by(|a, b| (a.rho - b.rho).abs() < 1e-12 && (a.z - b.z).abs() < 1e-12);
    pts
}

/// The revolved profile: positions (tool frame, mm) and triangle indices.
pub fn cutter_mesh(cutter: &Cutter) -> (Vec<f32>, Vec<u32>) {
    let pts = profile_points(cutter);
    let (mut pos, mut idx) = (Vec::new(), Vec::new());
    let mut rings: Vec<(u32, bool)> = Vec::new();
    for p in &pts {
        let start = (pos.len() / 3) as u32;
        let apex = p.rho.abs() < 1e-9;
        for m in 0..if apex { 1 } else { SLICES } {
            let a = std::f64::consts::TAU * m as f64 / SLICES as f64;
            pos.extend([p.rho * a.cos(), p.rho * a.sin(), p.z].map(|x| x as f32));
        }
        rings.push((start, apex));
    }
    let s = SLICES as u32;
    for w in rings.windows(2) {
        let ((a, a_apex), (b, b_apex)) = (w[0], w[1]);
        for m in 0..s {
            let n = (m + 1) % s;
            let at = |r: u32, apex: bool, k: u32| if apex { r } else { r + k };
            let (a0, a1, b0, b1) = (
                at(a, a_apex, m),
                at(a, a_apex, n),
                at(b, b_apex, m),
                at(b, b_apex, n),
            );
            if !a_apex {
                idx.extend([a0, a1, b1]);
            }
            if !b_apex {
                idx.extend([a0, b1, b0]);
            }
        }
    }
    (pos, idx)
}

/// The unit quaternion `[x, y, z, w]` turning +z onto `axis` (the shortest turn;
/// a half turn about x for -z).
pub fn rotation_to(axis: [f64; 3]) -> [f64; 4] {
    let n = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
    let [x, y, z] = axis.map(|c| c / n);
    if z < -1.0 + 1e-12 || !n.is_finite() || n == 0.0 {
        return if z < 0.0 {
            [1.0, 0.0, 0.0, 0.0]
        } else {
            [0.0, 0.0, 0.0, 1.0]
        };
    }
    let q = [-y, x, 0.0, 1.0 + z];
    let len = q.iter().map(|c| c * c).sum::<f64>().sqrt();
    q.map(|c| c / len)
}

/// Adds the cutter at `pose` to `glb` as the node `cutter` (mesh in the tool frame,
/// placed by translation and rotation; module doc); the node's index.
///
/// # Units
/// mm.
pub fn add_cutter(glb: &mut Glb, cutter: &Cutter, pose: &Pose) -> usize {
    let (pos, idx) = cutter_mesh(cutter);
    let p = glb.floats(&pos, "VEC3", 3);
    let i = glb.indices(&idx);
    let [r, g, b] = STEEL.map(linear);
    let mat = glb.material("cutter", [r, g, b, 1.0], 0.8);
    let node = glb.mesh_node("cutter", &[("POSITION", p)], Some(i), TRIANGLES, mat);
    glb.set_node(
        node,
        "translation",
        json!([pose.cl.x, pose.cl.y, pose.cl.z]),
    );
    let a = pose.axis;
    glb.set_node(node, "rotation", json!(rotation_to([a.x, a.y, a.z])));
    glb.set_node(node, "extras", json!({ "tool": cutter.to_string() }));
    node
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ball_profile_runs_tip_to_top_on_the_axis() {
        let ball = Cutter::ball(8.0, Some(20.0)).unwrap();
        let pts = profile_points(&ball);
        assert_eq!(pts[0].rho, 0.0);
        assert_eq!(pts[0].z, 0.0);
        let top = pts.last().unwrap();
        assert!(top.rho == 0.0 && (top.z - 20.0).abs() < 1e-12);
        for p in &pts[..pts.len() - 1] {
            let h = ball.height_at_radius(p.rho).unwrap();
            assert!(p.z >= h - 1e-9, "{p:?} below the profile {h}");
        }
    }

    #[test]
    fn rotations_turn_z_onto_the_axis() {
        for axis in [
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 0.0],
            [0.3, -0.4, 0.866],
            [0.0, 0.0, -1.0],
        ] {
            let [x, y, z, w] = rotation_to(axis);
            // q * (0,0,1) * q^-1, third column of the rotation matrix.
            let v = [
                2.0 * (x * z + w * y),
                2.0 * (y * z - w * x),
                1.0 - 2.0 * (x * x + y * y),
            ];
            let n = (axis.iter().map(|c| c * c).sum::<f64>()).sqrt();
            for k in 0..3 {
                assert!((v[k] - axis[k] / n).abs() < 1e-12, "{axis:?} -> {v:?}");
            }
        }
    }
}
