//! The paper's claim (issue 13) on both shared edge parts: the snug drop-and-spin
//! passes leave less material at the common edge than the vertical three-axis tool
//! touching both faces there, and never less than an insert can (the ball bound
//! `r (sec b - 1)`); neither gouges. Inclined single-point positioning along the same
//! edge is measured beside them and must not gouge either (with this cutter the
//! spun tool's flute binds before the ball limit, and the inclined tool's flat bottom
//! comes nearer the edge: the figures are printed). Every program is written as APT
//! CL, read back and cut on a dexel stock ([`swarf_app::edge_compare`]).

use swarf_app::edge_compare::{CELL, compare_edge, edge_markdown};

#[test]
fn on_the_concave_edge_the_snug_passes_leave_less_and_gouge_nothing() {
    claim("edge-concave");
}

#[test]
fn on_the_convex_edge_the_snug_passes_leave_less_and_gouge_nothing() {
    claim("edge-convex");
}

/// The claim on the shared edge part `name` (module doc), its figures printed.
fn claim(name: &str) {
    let text = include_str!("../../../jobs/edge-concave-drop-spin.toml");
    let job = swarf_app::Job::parse(&text.replace("edge-concave", name), "snug.toml").unwrap();
    let part = swarf_io::builtin_part(name).unwrap();
    let cmp = compare_edge(&job, &part).unwrap();
    let [snug, three, inclined] = [&cmp.rows[0], &cmp.rows[1], &cmp.rows[2]];
    assert_eq!(snug.passes, 2, "one snug pass per band");
    for (k, &d) in snug.left_mm.iter().enumerate() {
        let bound = cmp.ball_bound_mm[k];
        assert!(
            d < three.left_mm[k],
            "{name}: snug {d} not below three-axis {three:?}"
        );

        // A cell centre lies up to half a diagonal off the edge, where the faces
        // rise at slope b at most (tan b < 1 on these parts).
        assert!(
            d >= bound - CELL,
            "{name}: snug {d} below the ball bound {bound}"
        );
    }
    assert!(
        snug.gouge_mm <= job.tolerance(),
        "{name}: gouge {}",
        snug.gouge_mm
    );
    assert!(
        three.gouge_mm <= job.tolerance(),
        "{name}: gouge {}",
        three.gouge_mm
    );
    assert!(
        inclined.gouge_mm <= job.tolerance(),
        "{name}: gouge {}",
        inclined.gouge_mm
    );
    assert!(
        inclined
            .left_mm
            .iter()
            .all(|l| (0.0..three.left_mm[0]).contains(l)),
        "{inclined:?}"
    );
    eprintln!("{}", edge_markdown(&[cmp]));
}
