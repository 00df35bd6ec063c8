//! The house style's sizes and names, checked on the source text: no
//! source file over 800 lines, no function over 120, and no two public
//! types of the crate with one name.
#![cfg(not(target_arch = "wasm32"))]

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

const MAX_FILE_LINES: usize = 800;
const MAX_FN_LINES: usize = 120;

fn sources(dirs: &[&str], ext: &str) -> Vec<(String, String)> {
    fn walk(dir: &Path, ext: &str, out: &mut Vec<PathBuf>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        for e in entries.flatten() {
            let p = e.path();
            let skip = p
                .file_name()
                .is_some_and(|n| n == "pkg" || n == "vendor" || n == "node_modules");
            if p.is_dir() && !skip {
                walk(&p, ext, out);
            } else if p.extension().is_some_and(|e| e == ext) {
                out.push(p);
            }
        }
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut paths = Vec::new();
    for d in dirs {
        walk(&root.join(d), ext, &mut paths);
    }
    paths.sort();
    paths
        .into_iter()
        .map(|p| {
            let text = std::fs::read_to_string(&p).expect("a source file reads");
            let rel = p.strip_prefix(root).unwrap_or(&p).display().to_string();
            (rel, text)
        })
        .collect()
}

#[test]
fn no_source_file_is_over_800_lines() {
    let mut files = sources(&["src", "tests", "benches"], "rs");
    files.extend(sources(&["www", "tests/e2e", "benches"], "js"));
    files.extend(sources(&["www", "tests/e2e", "benches"], "mjs"));
    let long: Vec<String> = files
        .iter()
        .map(|(p, t)| (p, t.lines().count()))
        .filter(|&(_, n)| n > MAX_FILE_LINES)
        .map(|(p, n)| format!("{p}: {n} lines"))
        .collect();
    assert!(
        long.is_empty(),
        "files over {MAX_FILE_LINES} lines:\n{}",
        long.join("\n")
    );
}

/// The functions of formatted Rust source and their lengths in lines: from
/// the `fn` line to the closing brace at its indentation.
fn rust_functions(text: &str) -> Vec<(String, usize)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let trimmed = line.trim_start();
        let indent = &line[..line.len() - trimmed.len()];
        let head = trimmed
            .trim_start_matches("pub ")
            .trim_start_matches("pub(crate) ")
            .trim_start_matches("pub(super) ")
            .trim_start_matches("const ")
            .trim_start_matches("unsafe ");
        let Some(rest) = head.strip_prefix("fn ") else {
            continue;
        };
        let name: String = rest
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        // The signature ends at the first line ending in `{` (a body
        // follows) or `;` (a trait's declaration without one).
        let Some(sig) = lines[i..]
            .iter()
            .position(|l| l.trim_end().ends_with('{') || l.trim_end().ends_with(';'))
        else {
            continue;
        };
        let end = if lines[i + sig].trim_end().ends_with(';') {
            sig + 1
        } else {
            let close = format!("{indent}}}");
            lines[i + sig..]
                .iter()
                .position(|l| *l == close)
                .map_or(lines.len() - i, |k| sig + k + 1)
        };
        out.push((name, end));
    }
    out
}

#[test]
fn no_function_is_over_120_lines() {
    let mut long = Vec::new();
    for (path, text) in sources(&["src", "tests", "benches"], "rs") {
        for (name, n) in rust_functions(&text) {
            if n > MAX_FN_LINES {
                long.push(format!("{path}: fn {name}: {n} lines"));
            }
        }
    }
    assert!(
        long.is_empty(),
        "functions over {MAX_FN_LINES} lines:\n{}",
        long.join("\n")
    );
}

#[test]
fn function_lengths_are_measured_to_their_closing_brace() {
    let text = "fn a() {\n    x();\n}\n\ntrait S {\n    fn c(\n        &self,\n    ) -> u32;\n}\n\nimpl T {\n    pub fn b(\n        &self,\n    ) {\n        if y {\n        }\n    }\n}\n";
    let got: Vec<(String, usize)> = rust_functions(text);
    let want = [("a", 3), ("c", 3), ("b", 6)].map(|(n, l)| (n.to_string(), l));
    assert_eq!(got, want);
}

/// The public types (`pub struct`, `pub enum`, `pub trait`, `pub type`) of
/// `src/`, by name, with the files that declare them.
fn public_types() -> BTreeMap<String, Vec<String>> {
    let mut by_name: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for (path, text) in sources(&["src"], "rs") {
        for line in text.lines() {
            let t = line.trim_start();
            for kw in ["pub struct ", "pub enum ", "pub trait ", "pub type "] {
                if let Some(rest) = t.strip_prefix(kw) {
                    let name: String = rest
                        .chars()
                        .take_while(|c| c.is_alphanumeric() || *c == '_')
                        .collect();
                    // (`named_enum!` spells its type `$T`.)
                    if !name.is_empty() {
                        by_name.entry(name).or_default().push(path.clone());
                    }
                }
            }
        }
    }
    by_name
}

#[test]
fn no_two_public_types_share_a_name() {
    let shared: Vec<String> = public_types()
        .into_iter()
        .filter(|(_, files)| files.len() > 1)
        .map(|(name, files)| format!("{name}: {}", files.join(", ")))
        .collect();
    assert!(
        shared.is_empty(),
        "public types that share a name:\n{}",
        shared.join("\n")
    );
}

/// Test files that need a binary of their own: a global allocator, or
/// `run_in_browser` (set once per wasm test binary).
const OWN_BINARY: [&str; 3] = ["infra_browser.rs", "memory.rs", "wasm_facade.rs"];

#[test]
fn integration_tests_are_modules_of_the_suite() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let main = std::fs::read_to_string(root.join("tests/suite/main.rs")).expect("the suite reads");
    let mut stray = Vec::new();
    for e in std::fs::read_dir(root.join("tests"))
        .expect("tests/ reads")
        .flatten()
    {
        let name = e.file_name().to_string_lossy().to_string();
        if name.ends_with(".rs") && !OWN_BINARY.contains(&name.as_str()) {
            stray.push(format!(
                "tests/{name}: move it to tests/suite/ and add `mod` for it"
            ));
        }
    }
    for e in std::fs::read_dir(root.join("tests/suite"))
        .expect("tests/suite reads")
        .flatten()
    {
        let name = e.file_name().to_string_lossy().to_string();
        let module = name.strip_suffix(".rs").unwrap_or(&name);
        let is_module = e.path().is_dir() || name.ends_with(".rs");
        if is_module && module != "main" && !main.contains(&format!("mod {module};")) {
            stray.push(format!(
                "tests/suite/{name}: not declared in tests/suite/main.rs, so it never runs"
            ));
        }
    }
    assert!(
        stray.is_empty(),
        "each its own binary, linked and run apart:\n{}",
        stray.join("\n")
    );
}
