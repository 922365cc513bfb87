//! `haphe demo` (placeholder until the simulated session exists).
use std::process::ExitCode;
/// Arguments of `haphe demo`.
#[derive(clap::Args, Debug)]
pub struct Args {}
/// Runs the demo.
pub fn run(_args: &Args) -> anyhow::Result<ExitCode> {
    Ok(ExitCode::SUCCESS)
}
