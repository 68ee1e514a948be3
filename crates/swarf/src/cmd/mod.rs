//! One file per subcommand.

pub mod classify;
pub mod compare;
pub mod demo;
pub mod drop;
pub mod dsm;
pub mod eval;
pub mod inspect;
pub mod plan;
pub mod rest;
pub mod tessellate;
pub mod verify;
