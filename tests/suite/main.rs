//! The integration tests, one module per topic, in one test binary: one link
//! instead of thirty, and libtest spreads all of them over the machine's cores
//! (separate binaries run one after another). `tests/memory.rs` keeps its own
//! binary for its counting allocator, and the browser-only wasm tests theirs
//! for `run_in_browser`. Run one topic with `cargo test --test suite theorems::`.

mod common;

mod bound;
mod branch;
mod build_script;
mod calibration;
mod cli;
mod cli_properties;
mod cli_provenance;
mod committed_results;
mod determinism;
mod docs_commands;
mod experiment;
mod experiment_tables;
mod fidelity;
mod geometry;
mod infra_node;
mod layers;
mod paired;
mod paper_code;
mod phase_records;
mod phases;
mod planners;
mod statistics;
mod style;
mod theorems;
mod tidy;
mod timeline;
mod trap;
mod tree_split;
mod wasm_teach;
