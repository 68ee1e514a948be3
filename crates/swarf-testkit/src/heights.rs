//! Two height fields (dexel stocks) compared cell by cell against a 3D distance bound.

/// The largest `|fast - slow|` over `allowed * sqrt(1 + s^2)` among cells whose
/// `slow` surface is no steeper than 2:1 (`s` its steepest one-sided slope towards
/// the four neighbours: the vertical image of a 3D gap `allowed` on a plane of slope
/// `s`) and that `include` admits (by row-major index), and how many cells were
/// compared. Both fields are `nx` x `ny` cells of side `cell`, row-major; the border
/// cells are not compared.
pub fn worst_height_ratio(
    (slow, fast): (&[f64], &[f64]),
    (nx, ny, cell): (usize, usize, f64),
    allowed: f64,
    include: impl Fn(usize) -> bool,
) -> (f64, usize) {
    let (mut worst, mut count) = (0.0f64, 0);
    for j in 1..ny.saturating_sub(1) {
        for i in 1..nx.saturating_sub(1) {
            let k = j * nx + i;
            let slope = [k - 1, k + 1, k - nx, k + nx]
                .iter()
                .map(|&n| (slow[n] - slow[k]).abs() / cell)
                .fold(0.0, f64::max);
            if slope.is_nan() || slope > 2.0 || !slow[k].is_finite() || !include(k) {
                continue;
            }
            count += 1;
            worst = worst.max((fast[k] - slow[k]).abs() / (allowed * (1.0 + slope * slope).sqrt()));
        }
    }
    (worst, count)
}
