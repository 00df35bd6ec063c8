//! Native command-line interface.

fn main() {}
