//! Embeds the files `lectern` carries inside its binary: the scene shaders (used when a
//! project has no `shaders/` folder of its own) and the starter project that `lectern new`
//! writes. Generated from the folders themselves, so a shader added to `shaders/` or a file
//! added to `starter/` is carried without a list to keep in step.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
    entries.sort();
    for e in entries {
        if e.is_dir() {
            files(&e, out);
        } else {
            out.push(e);
        }
    }
}

/// `pub const NAME: &[(&str, &[u8])]`: (path relative to `dir`, bytes) of every file under it
/// (`only_ext`: just those).
fn table(code: &mut String, name: &str, dir: &Path, only_ext: Option<&str>) {
    println!("cargo:rerun-if-changed={}", dir.display());
    let mut all = Vec::new();
    files(dir, &mut all);
    writeln!(code, "pub const {name}: &[(&str, &[u8])] = &[").unwrap();
    for f in all {
        if only_ext.is_some_and(|x| f.extension().is_none_or(|e| e != x)) {
            continue;
        }
        println!("cargo:rerun-if-changed={}", f.display());
        let rel = f
            .strip_prefix(dir)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        let abs = f.canonicalize().unwrap();
        writeln!(
            code,
            "    ({rel:?}, include_bytes!({:?})),",
            abs.display().to_string()
        )
        .unwrap();
    }
    writeln!(code, "];").unwrap();
}

fn main() {
    let root = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").unwrap());
    let mut code = String::new();
    table(&mut code, "SHADERS", &root.join("shaders"), Some("wgsl"));
    table(&mut code, "STARTER", &root.join("starter"), None);
    let out = PathBuf::from(std::env::var("OUT_DIR").unwrap()).join("bundled.rs");
    std::fs::write(out, code).unwrap();
}
