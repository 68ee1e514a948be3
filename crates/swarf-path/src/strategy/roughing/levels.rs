//! Roughing levels: `step_down` apart from the stock's top down to the part's lowest
//! point plus the allowance, and one on every flat of the part (its height plus the
//! allowance), so that a floor between two levels keeps no more than the allowance.

use crate::error::PathError;
use swarf_geom::TriMesh;

/// Most levels one roughing may have.
pub const MAX_LEVELS: usize = 10_000;
/// A triangle is flat when its normal is within this of vertical, radians.
const FLAT_ANGLE: f64 = 0.5 * std::f64::consts::PI / 180.0;
/// Levels closer than this are one, mm.
const MERGE: f64 = 1e-4;

/// Tip heights of the levels, from the top down (module doc).
///
/// # Errors
/// [`PathError::InvalidParameter`] on `step_down` when there would be more
/// than [`MAX_LEVELS`] levels.
pub(crate) fn levels(
    mesh: &TriMesh,
    top: f64,
    allowance: f64,
    step_down: f64,
) -> Result<Vec<f64>, PathError> {
    let bottom = mesh.aabb().min.z + allowance;
    let count = ((top - bottom) / step_down).ceil();
    if count > MAX_LEVELS as f64 {
        return Err(PathError::InvalidParameter {
            field: "step_down".into(),
            message: format!(
                "{step_down} mm from {top:.3} down to {bottom:.3} mm makes {count:.0} levels, \
                 more than {MAX_LEVELS}: expected a larger step"
            ),
        });
    }
    if top <= bottom {
        return Ok(Vec::new());
    }
    let mut out: Vec<f64> = (1..count as usize)
        .map(|j| top - step_down * j as f64)
        .collect();
    out.push(bottom);
    let cos = FLAT_ANGLE.cos();
    for t in 0..mesh.len() {
        let Some(n) = mesh.normal(t) else { continue };
        if n.z.abs() < cos {
            continue;
        }
        let tri = mesh.triangle(t);
        let z = (tri[0].z + tri[1].z + tri[2].z) / 3.0 + allowance;
        if z < top && z >= bottom && out.len() < 2 * MAX_LEVELS {
            out.push(z);
        }
    }
    out.sort_by(|a, b| b.total_cmp(a));
    out.dedup_by(|a, b| (*b - *a).abs() < MERGE);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_geom::Point3;

    #[test]
    fn levels_step_down_and_stop_on_flats() {
        // A floor at z = 0 and a shelf at z = 3.3 (two flat triangles).
        let p = Point3::new;
        let mesh = TriMesh::from_triangles(&[
            [p(0.0, 0.0, 0.0), p(10.0, 0.0, 0.0), p(0.0, 10.0, 0.0)],
            [p(0.0, 0.0, 3.3), p(10.0, 0.0, 3.3), p(0.0, 10.0, 3.3)],
        ]);
        let z = levels(&mesh, 10.0, 0.5, 2.0).unwrap();
        let want = [8.0, 6.0, 4.0, 3.8, 2.0, 0.5];
        assert_eq!(z.len(), want.len(), "{z:?}");
        assert!(
            z.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-12),
            "{z:?}"
        );
        assert!(levels(&mesh, 1e9, 0.5, 1e-3).is_err());
        assert!(levels(&mesh, 0.2, 0.5, 1.0).unwrap().is_empty());
    }
}
