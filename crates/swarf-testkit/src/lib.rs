//! swarf-testkit: the fixtures that the workspace's tests share, written once (dev-only,
//! never published; every crate takes it as a dev-dependency).
//!
//! - [`boss`]: the built-in boss measured where a ball reaches it.
//! - [`heights`]: two dexel height fields compared against a 3D distance bound.
//! - [`parts`]: the built-in die and wave, the exact cylinder and the groove.
//! - [`machines`]: the example machine files and the repository root.
//! - [`references`]: whether independent references (OpenCAMLib, `rs274`) are
//!   required (`SWARF_REQUIRE_REFERENCES=1`), and skipping when they are not.
//! - [`rs274`]: LinuxCNC's standalone interpreter `rs274 -g` as a reference.
//! - [`threads`]: a computation on a given number of threads.
//! - `die_cc` (feature `plan`): the CC paths of the die experiment.
//!
//! Fixtures only: independent oracles (brute-force samplers, closed forms) stay next
//! to the tests they serve and share no code with what they check.

pub mod boss;
#[cfg(feature = "plan")]
mod die;
pub mod heights;
pub mod machines;
pub mod ocl;
pub mod parts;
pub mod references;
pub mod rs274;
pub mod threads;

#[cfg(feature = "plan")]
pub use die::die_cc;
