//! Independent references (OpenCAMLib heights, LinuxCNC's `rs274`) are optional: a
//! test that needs one skips when it is absent, unless `SWARF_REQUIRE_REFERENCES=1`,
//! which makes the absence a failure.

/// True when `SWARF_REQUIRE_REFERENCES=1`.
pub fn references_required() -> bool {
    std::env::var("SWARF_REQUIRE_REFERENCES").as_deref() == Ok("1")
}

/// Notes that the reference `what` is missing (`why`) and the check skipped.
///
/// # Panics
/// When references are required ([`references_required`]): the test fails.
pub fn skip_reference(what: &str, why: &str) {
    assert!(
        !references_required(),
        "{what} is required (SWARF_REQUIRE_REFERENCES=1) but cannot be used: {why}"
    );
    eprintln!("{what} not available ({why}): check skipped");
}
