//! build.rs embeds the commit of a git checkout of the crate, marks a tree
//! with changes as dirty, and gives `unknown` (never an error) outside one:
//! a tarball, or a copy inside another repository.
#![cfg(not(target_arch = "wasm32"))]

#[allow(dead_code)]
#[path = "../../build.rs"]
mod build_rs;

use std::path::Path;
use std::process::Command;

fn git(dir: &Path, args: &[&str]) {
    let ok = Command::new("git")
        .arg("-C")
        .arg(dir)
        .args(["-c", "user.name=t", "-c", "user.email=t@example.org"])
        .args(args)
        .output()
        .unwrap()
        .status
        .success();
    assert!(ok, "git {args:?}");
}

#[test]
fn the_commit_is_embedded_only_from_a_checkout_of_the_crate() {
    if Command::new("git").arg("--version").output().is_err() {
        eprintln!("git is not installed: only the no-git case can be checked");
    }
    let root = std::env::temp_dir().join(format!("torus-build-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    let crate_dir = root.join("crate");
    std::fs::create_dir_all(&crate_dir).unwrap();
    std::fs::write(crate_dir.join("Cargo.toml"), "[package]\n").unwrap();
    // Not a repository (a tarball): unknown.
    assert_eq!(build_rs::commit_of(&crate_dir), None);
    if Command::new("git").arg("--version").output().is_ok() {
        // The crate inside another repository: that commit is not the crate's.
        git(&root, &["init", "-q"]);
        git(&root, &["add", "."]);
        git(&root, &["commit", "-q", "-m", "outer"]);
        assert_eq!(build_rs::commit_of(&crate_dir), None);
        // A checkout of the crate: its HEAD, clean; then dirty after an edit.
        git(&crate_dir, &["init", "-q"]);
        git(&crate_dir, &["add", "."]);
        git(&crate_dir, &["commit", "-q", "-m", "crate"]);
        let (commit, dirty) = build_rs::commit_of(&crate_dir).unwrap();
        assert_eq!(commit.len(), 40);
        assert!(commit.bytes().all(|b| b.is_ascii_hexdigit()));
        assert!(!dirty);
        std::fs::write(crate_dir.join("Cargo.toml"), "[package]\nname = \"x\"\n").unwrap();
        assert_eq!(build_rs::commit_of(&crate_dir), Some((commit, true)));
        // What the script watches exists or is left out.
        let watched = build_rs::watched(&crate_dir);
        assert!(watched.iter().any(|p| p.ends_with("HEAD")));
        assert!(watched.iter().any(|p| p.ends_with("Cargo.toml")));
    }
    std::fs::remove_dir_all(&root).unwrap();
}
