//! Smoke test that the wasm test suite runs in Node.js (the default for
//! wasm-bindgen-test files without `run_in_browser`). Owned by the build/CI
//! setup; feature tests belong in their own files.
#![cfg(target_arch = "wasm32")]

use wasm_bindgen::JsValue;
use wasm_bindgen_test::*;

#[wasm_bindgen_test]
fn runs_in_node_without_a_window() {
    let global = js_sys::global();
    let window = js_sys::Reflect::get(&global, &JsValue::from_str("window")).unwrap();
    assert!(
        window.is_undefined(),
        "expected no `window` global in Node.js"
    );
}

#[wasm_bindgen_test]
fn version_is_the_crate_version() {
    assert_eq!(torus_search::wasm::version(), env!("CARGO_PKG_VERSION"));
}
