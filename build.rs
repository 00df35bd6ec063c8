//! Embeds the git commit the crate is built from, so every output can name
//! it (src/experiment/provenance.rs): `TORUS_SEARCH_COMMIT` is the 40-digit
//! hash of HEAD; `TORUS_SEARCH_DIRTY` is `true` when the tree differs from
//! it (`git status --porcelain` lists a change or an untracked file).
//! Outside a git checkout of this crate (a tarball, a copy vendored inside
//! another repository, no git installed) both are `unknown`, and the build
//! goes on.

use std::path::{Path, PathBuf};
use std::process::Command;

/// `git ARGS` run in `dir`: its trimmed stdout, or `None` if it failed.
fn git(dir: &Path, args: &[&str]) -> Option<String> {
    let out = Command::new("git")
        .arg("-C")
        .arg(dir)
        .args(args)
        .output()
        .ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_string())
}

/// The commit of the checkout whose top level is `dir`, and whether its
/// tracked files differ from it; `None` when `dir` is not the top of a git
/// checkout (another repository's commit would not describe this crate).
pub fn commit_of(dir: &Path) -> Option<(String, bool)> {
    let top = PathBuf::from(git(dir, &["rev-parse", "--show-toplevel"])?);
    let same = |a: &Path, b: &Path| match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    };
    if !same(&top, dir) {
        return None;
    }
    let head = git(dir, &["rev-parse", "--verify", "HEAD"])?;
    if head.len() != 40 || !head.bytes().all(|b| b.is_ascii_hexdigit()) {
        return None;
    }
    let status = git(dir, &["status", "--porcelain"])?;
    Some((head, !status.is_empty()))
}

/// What invalidates the embedded values: HEAD, the index and the refs (a
/// commit, a checkout) and every tracked part of the tree (an edit makes it
/// dirty). Generated directories are left out, or every build would rerun.
pub fn watched(dir: &Path) -> Vec<PathBuf> {
    const SKIP: &[&str] = &[".git", "target", "node_modules", "dist", "pkg", "vendor"];
    let mut out = Vec::new();
    if let Some(git_dir) = git(dir, &["rev-parse", "--absolute-git-dir"]) {
        let git_dir = PathBuf::from(git_dir);
        out.extend([git_dir.join("HEAD"), git_dir.join("index")]);
        if let Some(common) = git(dir, &["rev-parse", "--git-common-dir"]) {
            let common = dir.join(common);
            out.extend([common.join("refs"), common.join("packed-refs")]);
        }
    }
    for sub in [dir.to_path_buf(), dir.join("www")] {
        let Ok(entries) = std::fs::read_dir(&sub) else {
            continue;
        };
        for e in entries.flatten() {
            let name = e.file_name();
            let name = name.to_string_lossy();
            // www is walked on its own, for its generated pkg and vendor.
            let www = sub == dir && name == "www";
            if !(SKIP.contains(&name.as_ref()) || www) {
                out.push(e.path());
            }
        }
    }
    out
}

fn main() {
    let dir = PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").expect("cargo sets it"));
    let (commit, dirty) = match commit_of(&dir) {
        Some((c, d)) => (c, d.to_string()),
        None => ("unknown".to_string(), "unknown".to_string()),
    };
    println!("cargo:rustc-env=TORUS_SEARCH_COMMIT={commit}");
    println!("cargo:rustc-env=TORUS_SEARCH_DIRTY={dirty}");
    println!("cargo:rerun-if-changed=build.rs");
    // A path that does not exist would rerun the script on every build.
    for p in watched(&dir).into_iter().filter(|p| p.exists()) {
        println!("cargo:rerun-if-changed={}", p.display());
    }
}
