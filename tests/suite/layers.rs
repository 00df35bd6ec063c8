//! The crate's modules form layers that only point down, with no import
//! cycle between modules.
//!
//! Every `src/**/*.rs` file is read as text. A module's imports are the
//! paths it names (`crate::…`, `super::…`, `self::…` and its own child
//! modules), outside test code (`#[cfg(test)]` items and the files of test
//! modules) and outside re-exports (`pub use`). A path is resolved to the
//! deepest module it names, through re-exports to the module that defines
//! the item. `docs/ARCHITECTURE.md` gives the layers.
#![cfg(not(target_arch = "wasm32"))]

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Module path prefixes and their layer, lowest first. A module belongs to
/// the longest prefix that names it; `""` is the crate root.
const LAYERS: &[(&str, u32)] = &[
    ("game", 0),
    ("param", 1),
    ("searchers", 2),
    ("config", 3),
    ("run", 4),
    ("analysis", 5),
    ("display", 5),
    ("experiment", 6),
    ("bench", 6),
    ("cli", 7),
    ("wasm", 7),
    ("", 8),
];

#[test]
fn layers_only_point_down_and_no_module_imports_in_a_cycle() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let files = read_tree(&root);
    let graph = Graph::of(&files);
    let cycles = graph.cycles();
    let described: Vec<String> = cycles
        .iter()
        .map(|c| {
            let inside: Vec<String> = c
                .iter()
                .flat_map(|m| {
                    graph.edges[m]
                        .iter()
                        .filter(|t| c.contains(t))
                        .map(move |t| format!("  {m} -> {t}"))
                })
                .collect();
            format!("{}\n{}", c.join(", "), inside.join("\n"))
        })
        .collect();
    assert!(
        cycles.is_empty(),
        "import cycles between modules (each cycle's modules, then its imports):\n{}",
        described.join("\n")
    );
    let mut upward = Vec::new();
    for (from, tos) in &graph.edges {
        for to in tos {
            let (lf, lt) = (layer(from), layer(to));
            assert!(lf.is_some(), "module {from} has no layer in LAYERS");
            if lt > lf {
                upward.push(format!("{from} (layer {lf:?}) imports {to} (layer {lt:?})"));
            }
        }
    }
    assert!(
        upward.is_empty(),
        "imports that point up:\n{}",
        upward.join("\n")
    );
}

#[test]
fn a_cycle_or_an_upward_import_is_found() {
    // A stand-in crate: `game::a` imports `searchers::b` (upward) and
    // `searchers::b` imports `game::a` (a cycle). Test code, re-exports and
    // comments must not count.
    let files = vec![
        file("", "mod game; mod searchers;"),
        file("game", "pub mod a; pub use a::Thing;"),
        file(
            "game::a",
            "use crate::searchers::b::Other; // crate::run::x\npub struct Thing;\n\
             #[cfg(test)]\nmod tests { use crate::config::Config; }",
        ),
        file("searchers", "pub mod b;"),
        file(
            "searchers::b",
            "pub struct Other; fn f() -> crate::game::Thing { let s = \"crate::cli\"; crate::game::Thing }",
        ),
    ];
    let g = Graph::of(&files);
    assert_eq!(g.cycles(), vec![vec!["game::a", "searchers::b"]]);
    let a: Vec<&String> = g.edges["game::a"].iter().collect();
    assert_eq!(a, ["searchers::b"], "comments and test code do not count");
    let b: Vec<&String> = g.edges["searchers::b"].iter().collect();
    assert_eq!(b, ["game::a"], "a re-export resolves to its source");
    // Without the upward import there is no cycle.
    let mut fixed = files.clone();
    fixed[2].text = "pub struct Thing;".into();
    assert!(Graph::of(&fixed).cycles().is_empty());
}

fn file(module: &str, text: &str) -> Source {
    Source {
        module: module.into(),
        text: text.into(),
        test_only: false,
    }
}

fn layer(module: &str) -> Option<u32> {
    LAYERS
        .iter()
        .filter(|(prefix, _)| {
            prefix.is_empty() || module == *prefix || module.starts_with(&format!("{prefix}::"))
        })
        .max_by_key(|(prefix, _)| prefix.len())
        .map(|&(_, l)| l)
}

/// One source file: its module path and its text.
#[derive(Clone)]
struct Source {
    module: String,
    text: String,
    test_only: bool,
}

/// Reads every `.rs` file under `root` (`src/`), skipping the binary and
/// marking the files of `#[cfg(test)]` modules.
fn read_tree(root: &Path) -> Vec<Source> {
    let mut paths = Vec::new();
    collect(root, &mut paths);
    let paths: Vec<PathBuf> = paths
        .into_iter()
        .filter(|p| p.file_name().is_some_and(|n| n != "main.rs"))
        .collect();
    // A `#[cfg(test)] mod x;` declaration makes x's file test code.
    let mut test_files = Vec::new();
    for p in &paths {
        let text = std::fs::read_to_string(p).expect("a source file reads");
        for (name, at) in test_mod_decls(&text) {
            test_files.push(module_file(p, &name, at.as_deref()));
        }
    }
    paths
        .iter()
        .map(|p| Source {
            module: module_of(root, p),
            text: std::fs::read_to_string(p).expect("a source file reads"),
            test_only: test_files.iter().any(|t| t == p),
        })
        .collect()
}

/// The file of module `name` declared in `file`: `#[path]`'s, relative to
/// `file`'s folder, or the default (`x.rs` or `x/mod.rs` beside a `mod.rs`
/// or `lib.rs`, else in the folder named after `file`).
fn module_file(file: &Path, name: &str, path_attr: Option<&str>) -> PathBuf {
    let dir = file.parent().expect("a file has a folder");
    if let Some(p) = path_attr {
        return dir.join(p);
    }
    let stem = file.file_stem().and_then(|s| s.to_str()).unwrap_or("");
    let base = if stem == "mod" || stem == "lib" {
        dir.to_path_buf()
    } else {
        dir.join(stem)
    };
    let flat = base.join(format!("{name}.rs"));
    if flat.exists() {
        flat
    } else {
        base.join(name).join("mod.rs")
    }
}

fn collect(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .expect("src reads")
        .map(|e| e.expect("an entry").path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            collect(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// `src/a/b.rs` → `a::b`, `src/a/mod.rs` → `a`, `src/lib.rs` → ``.
fn module_of(root: &Path, path: &Path) -> String {
    let rel = path.strip_prefix(root).expect("under src");
    let mut parts: Vec<String> = rel
        .with_extension("")
        .iter()
        .map(|s| s.to_string_lossy().into_owned())
        .collect();
    if matches!(parts.last().map(String::as_str), Some("mod" | "lib")) {
        parts.pop();
    }
    parts.join("::")
}

fn join(parent: &str, child: &str) -> String {
    if parent.is_empty() {
        child.to_string()
    } else {
        format!("{parent}::{child}")
    }
}

/// The module graph: for each module, the modules it imports.
struct Graph {
    edges: BTreeMap<String, BTreeSet<String>>,
}

impl Graph {
    fn of(files: &[Source]) -> Graph {
        let modules: BTreeSet<String> = files.iter().map(|f| f.module.clone()).collect();
        // Each module's re-exports: item name → the path it re-exports.
        let mut reexports: BTreeMap<String, BTreeMap<String, Vec<String>>> = BTreeMap::new();
        let mut code: BTreeMap<String, String> = BTreeMap::new();
        for f in files.iter().filter(|f| !f.test_only) {
            let text = strip_test_items(&strip_comments_and_strings(&f.text));
            let (rest, uses) = take_reexports(&text);
            let map = reexports.entry(f.module.clone()).or_default();
            for path in uses {
                let abs = absolute(&f.module, &path, &modules);
                if let Some(name) = path.last() {
                    map.insert(name.clone(), abs);
                }
            }
            code.insert(f.module.clone(), rest);
        }
        let mut edges = BTreeMap::new();
        for (module, text) in &code {
            let mut deps = BTreeSet::new();
            for path in paths_in(text) {
                let abs = absolute(module, &path, &modules);
                if abs.is_empty() {
                    continue;
                }
                if let Some(target) = resolve(&abs, &modules, &reexports, 0) {
                    if target != *module && !target.is_empty() {
                        deps.insert(target);
                    }
                }
            }
            edges.insert(module.clone(), deps);
        }
        Graph { edges }
    }

    /// The strongly connected components of more than one module, each
    /// sorted, in order.
    fn cycles(&self) -> Vec<Vec<String>> {
        let nodes: Vec<&String> = self.edges.keys().collect();
        let index: BTreeMap<&String, usize> =
            nodes.iter().enumerate().map(|(i, n)| (*n, i)).collect();
        let adj: Vec<Vec<usize>> = nodes
            .iter()
            .map(|n| {
                self.edges[*n]
                    .iter()
                    .filter_map(|t| index.get(t).copied())
                    .collect()
            })
            .collect();
        let mut out: Vec<Vec<String>> = tarjan(&adj)
            .into_iter()
            .filter(|c| c.len() > 1)
            .map(|c| {
                let mut names: Vec<String> = c.iter().map(|&i| nodes[i].clone()).collect();
                names.sort();
                names
            })
            .collect();
        out.sort();
        out
    }
}

/// Tarjan's strongly connected components, iteratively.
fn tarjan(adj: &[Vec<usize>]) -> Vec<Vec<usize>> {
    let n = adj.len();
    let (mut index, mut low) = (vec![usize::MAX; n], vec![0; n]);
    let (mut on_stack, mut stack, mut out) = (vec![false; n], Vec::new(), Vec::new());
    let mut next = 0;
    for start in 0..n {
        if index[start] != usize::MAX {
            continue;
        }
        let mut work = vec![(start, 0usize)];
        while let Some(&mut (v, ref mut i)) = work.last_mut() {
            if *i == 0 && index[v] == usize::MAX {
                index[v] = next;
                low[v] = next;
                next += 1;
                stack.push(v);
                on_stack[v] = true;
            }
            if let Some(&w) = adj[v].get(*i) {
                *i += 1;
                if index[w] == usize::MAX {
                    work.push((w, 0));
                } else if on_stack[w] {
                    low[v] = low[v].min(index[w]);
                }
                continue;
            }
            work.pop();
            if let Some(&(parent, _)) = work.last() {
                low[parent] = low[parent].min(low[v]);
            }
            if low[v] == index[v] {
                let mut comp = Vec::new();
                while let Some(w) = stack.pop() {
                    on_stack[w] = false;
                    comp.push(w);
                    if w == v {
                        break;
                    }
                }
                out.push(comp);
            }
        }
    }
    out
}

/// `path` (as written in `module`) as segments from the crate root, or
/// empty when it names nothing in this crate.
fn absolute(module: &str, path: &[String], modules: &BTreeSet<String>) -> Vec<String> {
    let mut base: Vec<String> = if module.is_empty() {
        Vec::new()
    } else {
        module.split("::").map(String::from).collect()
    };
    let mut segs = path.iter().peekable();
    match segs.peek().map(|s| s.as_str()) {
        Some("crate") => {
            segs.next();
            base.clear();
        }
        Some("self") => {
            segs.next();
        }
        Some("super") => {
            while segs.peek().map(|s| s.as_str()) == Some("super") {
                segs.next();
                base.pop();
            }
        }
        Some(first) => {
            // A child module of this one, named without `self::`.
            if !modules.contains(&join(module, first)) {
                return Vec::new();
            }
        }
        None => return Vec::new(),
    }
    base.extend(segs.cloned());
    base
}

/// The module that defines what `path` names: the deepest module the path
/// names, followed through that module's re-exports.
fn resolve(
    path: &[String],
    modules: &BTreeSet<String>,
    reexports: &BTreeMap<String, BTreeMap<String, Vec<String>>>,
    depth: u32,
) -> Option<String> {
    let k = (0..=path.len())
        .rev()
        .find(|&k| modules.contains(&path[..k].join("::")))?;
    let module = path[..k].join("::");
    if depth < 8 {
        if let Some(next) = path.get(k) {
            if let Some(target) = reexports.get(&module).and_then(|m| m.get(next)) {
                let mut p = target.clone();
                p.extend(path[k + 1..].iter().cloned());
                return resolve(&p, modules, reexports, depth + 1);
            }
        }
    }
    Some(module)
}

/// Blanks comments, string literals and char literals (keeping lengths and
/// newlines), so braces and paths inside them do not count.
fn strip_comments_and_strings(src: &str) -> String {
    let b: Vec<char> = src.chars().collect();
    let mut out = String::with_capacity(src.len());
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        let next = b.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < b.len() && b[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < b.len() {
                if b[i] == '/' && b.get(i + 1) == Some(&'*') {
                    depth += 1;
                    i += 2;
                } else if b[i] == '*' && b.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    out.push(if b[i] == '\n' { '\n' } else { ' ' });
                    i += 1;
                }
            }
        } else if c == 'r' && (next == Some('"') || next == Some('#')) && !ident_before(&b, i) {
            // A raw string r"…" or r#"…"#.
            let mut j = i + 1;
            let mut hashes = 0;
            while b.get(j) == Some(&'#') {
                hashes += 1;
                j += 1;
            }
            if b.get(j) != Some(&'"') {
                out.push(c);
                i += 1;
                continue;
            }
            j += 1;
            loop {
                if j >= b.len() {
                    break;
                }
                if b[j] == '"' && (0..hashes).all(|h| b.get(j + 1 + h) == Some(&'#')) {
                    j += 1 + hashes;
                    break;
                }
                j += 1;
            }
            out.push_str("\"\"");
            i = j;
        } else if c == '"' {
            i += 1;
            while i < b.len() && b[i] != '"' {
                if b[i] == '\\' {
                    i += 1;
                }
                if b.get(i) == Some(&'\n') {
                    out.push('\n');
                }
                i += 1;
            }
            i += 1;
            out.push_str("\"\"");
        } else if c == '\'' {
            // A char literal ('x', '\n', '\u{..}'), or a lifetime ('a).
            if next == Some('\\') {
                let mut j = i + 2;
                while j < b.len() && b[j] != '\'' {
                    j += 1;
                }
                i = j + 1;
                out.push_str("' '");
            } else if b.get(i + 2) == Some(&'\'') {
                i += 3;
                out.push_str("' '");
            } else {
                out.push(c);
                i += 1;
            }
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

fn ident_before(b: &[char], i: usize) -> bool {
    i > 0 && (b[i - 1].is_alphanumeric() || b[i - 1] == '_')
}

/// Removes every `#[cfg(test)]` item: up to its `;`, or its `{ … }` block.
fn strip_test_items(src: &str) -> String {
    let mut out = String::new();
    let mut rest = src;
    while let Some(at) = rest.find("#[cfg(test)]") {
        out.push_str(&rest[..at]);
        let after = &rest[at..];
        let end = item_end(after);
        rest = &after[end..];
    }
    out.push_str(rest);
    out
}

/// The byte length of the item that starts `s` (its attributes included):
/// up to the first `;` outside braces, or the brace that closes its block.
fn item_end(s: &str) -> usize {
    let mut depth = 0i32;
    let mut in_attr = 0i32;
    for (i, c) in s.char_indices() {
        match c {
            '[' => in_attr += 1,
            ']' => in_attr -= 1,
            '{' if in_attr == 0 => depth += 1,
            '}' if in_attr == 0 => {
                depth -= 1;
                if depth == 0 {
                    return i + 1;
                }
            }
            ';' if depth == 0 && in_attr == 0 => return i + 1,
            _ => {}
        }
    }
    s.len()
}

/// The `#[cfg(test)] mod name;` declarations in `src`: each name, with
/// its `#[path = "…"]` if it has one.
fn test_mod_decls(src: &str) -> Vec<(String, Option<String>)> {
    let mut out = Vec::new();
    let mut rest = src;
    while let Some(at) = rest.find("#[cfg(test)]") {
        let after = &rest[at..];
        let item = &after[..item_end(after)];
        if item.ends_with(';') {
            let words: Vec<&str> = item
                .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                .filter(|w| !w.is_empty())
                .collect();
            let path = item
                .split_once("path = \"")
                .and_then(|(_, rest)| rest.split_once('"'))
                .map(|(p, _)| p.to_string());
            if let Some(pos) = words.iter().position(|w| *w == "mod") {
                if let Some(name) = words.get(pos + 1) {
                    out.push((name.to_string(), path));
                }
            }
        }
        rest = &after[item.len().max(1)..];
    }
    out
}

/// Takes out the `pub use …;` and `pub(…) use …;` re-exports, returning
/// the rest and the paths they re-export.
fn take_reexports(src: &str) -> (String, Vec<Vec<String>>) {
    let mut out = String::new();
    let mut paths = Vec::new();
    let mut rest = src;
    loop {
        let found = ["pub use ", "pub(crate) use ", "pub(super) use "]
            .iter()
            .filter_map(|p| rest.find(p).map(|i| (i, p.len())))
            .min();
        let Some((at, len)) = found else { break };
        out.push_str(&rest[..at]);
        let tree_start = at + len;
        let end = rest[tree_start..]
            .find(';')
            .map_or(rest.len(), |e| tree_start + e);
        paths.extend(expand_use_tree(&rest[tree_start..end]));
        rest = &rest[(end + 1).min(rest.len())..];
    }
    out.push_str(rest);
    (out, paths)
}

/// `a::{b, c::{d, e as f}}` → `[a, b]`, `[a, c, d]`, `[a, c, e]` (a rename
/// keeps the source name; `self` in braces names the prefix).
fn expand_use_tree(tree: &str) -> Vec<Vec<String>> {
    fn go(prefix: &[String], s: &str, out: &mut Vec<Vec<String>>) {
        let s = s.trim();
        if let Some(open) = s.find('{') {
            let head: Vec<String> = segments(&s[..open]);
            let inner = &s[open + 1..s.rfind('}').unwrap_or(s.len())];
            let mut p = prefix.to_vec();
            p.extend(head);
            for part in split_top(inner) {
                if part.trim() == "self" {
                    out.push(p.clone());
                } else if !part.trim().is_empty() {
                    go(&p, part, out);
                }
            }
        } else {
            let s = s.split(" as ").next().unwrap_or(s);
            let mut p = prefix.to_vec();
            p.extend(segments(s));
            if p.last().map(String::as_str) == Some("self") {
                p.pop();
            }
            if p.last().map(String::as_str) != Some("*") && !p.is_empty() {
                out.push(p);
            }
        }
    }
    let mut out = Vec::new();
    go(&[], tree, &mut out);
    out
}

fn segments(s: &str) -> Vec<String> {
    s.split("::")
        .map(|x| x.trim().to_string())
        .filter(|x| !x.is_empty())
        .collect()
}

/// Splits at the commas outside braces.
fn split_top(s: &str) -> Vec<&str> {
    let (mut depth, mut start, mut out) = (0, 0, Vec::new());
    for (i, c) in s.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                out.push(&s[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    out.push(&s[start..]);
    out
}

/// Every path in `src`: the trees of its `use` declarations, and each run
/// of `ident::ident…` elsewhere.
fn paths_in(src: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let mut rest = String::new();
    let mut s = src;
    while let Some(at) = find_word(s, "use") {
        rest.push_str(&s[..at]);
        let end = s[at..].find(';').map_or(s.len(), |e| at + e);
        out.extend(expand_use_tree(&s[at + 3..end]));
        s = &s[(end + 1).min(s.len())..];
    }
    rest.push_str(s);
    let chars: Vec<char> = rest.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        if (chars[i].is_alphabetic() || chars[i] == '_') && !ident_before(&chars, i) {
            let mut segs = Vec::new();
            let mut j = i;
            loop {
                let start = j;
                while j < chars.len() && (chars[j].is_alphanumeric() || chars[j] == '_') {
                    j += 1;
                }
                segs.push(chars[start..j].iter().collect::<String>());
                if chars.get(j) == Some(&':') && chars.get(j + 1) == Some(&':') {
                    j += 2;
                    if chars.get(j).is_some_and(|c| c.is_alphabetic() || *c == '_') {
                        continue;
                    }
                }
                break;
            }
            if segs.len() > 1 {
                out.push(segs);
            }
            i = j.max(i + 1);
        } else {
            i += 1;
        }
    }
    out
}

/// The byte index of the next `word` that stands alone (not part of an
/// identifier).
fn find_word(s: &str, word: &str) -> Option<usize> {
    let bytes = s.as_bytes();
    let mut from = 0;
    while let Some(i) = s[from..].find(word) {
        let at = from + i;
        let before = at.checked_sub(1).map(|j| bytes[j]);
        let after = bytes.get(at + word.len()).copied();
        let is_ident = |c: Option<u8>| c.is_some_and(|c| c.is_ascii_alphanumeric() || c == b'_');
        if !is_ident(before) && !is_ident(after) && after.is_some_and(|c| c == b' ') {
            return Some(at);
        }
        from = at + word.len();
    }
    None
}

#[test]
fn paths_are_found_in_use_trees_and_code() {
    let src = strip_comments_and_strings(
        "use crate::{a::B, c::{d::E, F as G}};\nfn f<'a>(x: &'a str) -> char { let _ = super::h::I::new(); '{' }",
    );
    let mut p = paths_in(&src);
    p.sort();
    let want: Vec<Vec<String>> = [
        vec!["crate", "a", "B"],
        vec!["crate", "c", "F"],
        vec!["crate", "c", "d", "E"],
        vec!["super", "h", "I", "new"],
    ]
    .iter()
    .map(|v| v.iter().map(|s| s.to_string()).collect())
    .collect();
    assert_eq!(p, want);
    assert_eq!(
        item_end("#[cfg(test)]\nmod tests { fn a() {} }\nfn b() {}"),
        36
    );
}
