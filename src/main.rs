//! The `torus-search` binary: the command line of [`torus_search::cli`].

#[cfg(not(target_arch = "wasm32"))]
fn main() {
    std::process::exit(torus_search::cli::main());
}

#[cfg(target_arch = "wasm32")]
fn main() {}
