//! The hostile inputs of issue 15, each as the command a user ran: every one ended in
//! an abort, a hang, an unbounded read, a non-finite result with exit status 0, a
//! slow error without a place, or a broken output set. Each now ends within a few
//! seconds, in bounded memory, with an error that names its place (or, for output
//! sets, with the previous files whole).

mod fuzz_finds;
mod issue;
mod support;
