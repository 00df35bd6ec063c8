//! Smoke test that the wasm test suite really runs in headless Chromium
//! (via chromedriver and `webdriver.json`). Owned by the build/CI setup;
//! feature tests belong in their own files.
#![cfg(target_arch = "wasm32")]

use wasm_bindgen::JsValue;
use wasm_bindgen_test::*;

wasm_bindgen_test_configure!(run_in_browser);

#[wasm_bindgen_test]
fn runs_in_a_browser_with_a_window() {
    let global = js_sys::global();
    let window = js_sys::Reflect::get(&global, &JsValue::from_str("window")).unwrap();
    assert!(window.is_object(), "expected a browser `window` global");
}

#[wasm_bindgen_test]
fn version_is_the_crate_version() {
    assert_eq!(torus_search::wasm::version(), env!("CARGO_PKG_VERSION"));
}
