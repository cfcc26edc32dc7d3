//! `lectern new DIR [--title T]`: a starter project a lecturer can present at once — a deck with
//! one slide per kind of block and several widgets (commented), a problem file, a tableau, a
//! picture, the water scene and a README of its own. The files are built into the binary
//! (`build.rs` embeds `starter/`), so `new` works from any folder with no repository at hand.

use std::path::{Path, PathBuf};

use anyhow::Context as _;

/// Make a starter project (deck, problem file, tableau, picture, scene, README) in DIR.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The folder to create (it must not exist, or be empty).
    pub dir: PathBuf,
    /// The lecture's title, on its first slide and in its README [default: the folder's name].
    #[arg(long)]
    pub title: Option<String>,
    /// Also write the scene's shaders into DIR/shaders, to edit (without, the ones built into
    /// lectern are used).
    #[arg(long)]
    pub with_shaders: bool,
}

/// The deck `new` writes, relative to the project folder.
pub const DECK: &str = "slides/talk.ron";

/// Writes the starter project into `dir`; the files written, relative to it.
pub fn create(dir: &Path, title: &str, with_shaders: bool) -> anyhow::Result<Vec<String>> {
    if dir.exists() {
        let empty = std::fs::read_dir(dir)
            .with_context(|| format!("{}: cannot read", dir.display()))?
            .next()
            .is_none();
        anyhow::ensure!(
            empty,
            "{} already exists and is not empty: `lectern new` only writes into a new or empty folder",
            dir.display()
        );
    }
    let mut files: Vec<(String, Vec<u8>)> = crate::bundled::STARTER
        .iter()
        .map(|(rel, bytes)| (rel.to_string(), fill_in(rel, bytes, title)))
        .collect();
    files.push((
        "scenes/water.ron".into(),
        crate::bundled::WATER_SCENE.as_bytes().to_vec(),
    ));
    if with_shaders {
        for (name, bytes) in crate::bundled::SHADERS {
            files.push((format!("shaders/{name}"), bytes.to_vec()));
        }
    }
    for (rel, bytes) in &files {
        crate::bundled::write_atomic(&dir.join(rel), bytes)
            .with_context(|| format!("{}: cannot write", dir.join(rel).display()))?;
    }
    Ok(files.into_iter().map(|(rel, _)| rel).collect())
}

/// The title put into the deck and the README (`TITLE` in the starter files).
fn fill_in(rel: &str, bytes: &[u8], title: &str) -> Vec<u8> {
    let Ok(text) = std::str::from_utf8(bytes) else {
        return bytes.to_vec();
    };
    let title = if rel.ends_with(".ron") {
        // inside a RON string
        title.replace('\\', "\\\\").replace('"', "\\\"")
    } else {
        title.to_owned()
    };
    text.replace("TITLE", &title).into_bytes()
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let title = args.title.clone().unwrap_or_else(|| {
        (args.dir.file_name())
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "My lecture".into())
    });
    let written = create(&args.dir, &title, args.with_shaders)?;
    println!(
        "created {} ({} files): {DECK}, a problem file, a tableau, a picture, scenes/water.ron{}",
        args.dir.display(),
        written.len(),
        if args.with_shaders { ", shaders/" } else { "" }
    );
    let dir = args.dir.display();
    println!("next:  cd {dir} && lectern check {DECK} && lectern present {DECK}");
    Ok(())
}
