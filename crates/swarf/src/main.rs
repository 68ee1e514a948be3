//! The `swarf` command-line tool.

fn main() {}
