//! `lectern export`: Render every slide to PNG, headless.

/// Render every slide to PNG, headless.
#[derive(Debug, clap::Args)]
pub struct Args {}

pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`lectern export` is not built yet")
}
