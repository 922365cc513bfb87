//! The `haphe` command: a thin `main` that hands each subcommand to its module's `run` and maps
//! errors to exit codes.

mod args;
mod commands;
mod input;
mod output;
mod session;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

#[cfg(feature = "bench")]
use commands::bench;
#[cfg(not(all(feature = "view", feature = "bench")))]
use commands::missing;
#[cfg(feature = "view")]
use commands::view;
use commands::{build, demo, devices, generate, query, repair, run, simulate, validate, verify};

/// haphe: real-time haptic rendering against triangle meshes.
#[derive(Parser, Debug)]
#[command(name = "haphe", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Read mesh files and report every defect with where it is; report what a NIfTI-1
    /// volume file holds.
    #[command(after_help = validate::EXIT_CODES)]
    Validate(validate::Args),
    /// Repair a mesh into a closed solid (weld, drop degenerate and duplicate faces,
    /// orient, fill small holes), reporting each change; writes a new file.
    Repair(repair::Args),
    /// Build the voxel map of a mesh and save surface and map as one file.
    Build(build::Args),
    /// Answer inside/outside and segment-crossing queries from CSV files.
    Query(query::Args),
    /// Check haphe's queries against brute force and parry on a mesh.
    Verify(verify::Args),
    /// Write a procedural test mesh (binary STL).
    Generate(generate::Args),
    /// Run a simulated haptic session (simulated hand, scripted path or replayed trace).
    Simulate(simulate::Args),
    /// Run a haptic session with a device: dhd, openhaptics, udp:HOST:PORT or hand.
    Run(run::Args),
    /// List the haptic devices found: vendor libraries loaded or not, devices connected.
    Devices(devices::Args),
    /// A simulated hand explores built-in models; summary and plot (no files needed).
    Demo(demo::Args),
    /// Time haphe's queries beside parry3d-f64 and brute force, on procedural meshes and files.
    #[cfg(feature = "bench")]
    Bench(bench::Args),
    /// Time haphe's queries beside parry3d-f64 (not in this build: feature `bench`).
    #[cfg(not(feature = "bench"))]
    Bench(missing::Missing),
    /// A live 3D view in the browser: touch a mesh with the mouse, or replay a trace.
    #[cfg(feature = "view")]
    View(view::Args),
    /// A live 3D view in the browser (not in this build: feature `view`).
    #[cfg(not(feature = "view"))]
    View(missing::Missing),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Validate(args) => validate::run(&args),
        Command::Repair(args) => repair::run(&args),
        Command::Build(args) => build::run(&args),
        Command::Query(args) => query::run(&args),
        Command::Verify(args) => verify::run(&args),
        Command::Generate(args) => generate::run(&args),
        Command::Simulate(args) => simulate::run(&args),
        Command::Run(args) => run::run(&args),
        Command::Devices(args) => devices::run(&args),
        Command::Demo(args) => demo::run(&args),
        #[cfg(feature = "bench")]
        Command::Bench(args) => bench::run(&args),
        #[cfg(not(feature = "bench"))]
        Command::Bench(_) => Err(missing::missing("bench", "bench")),
        #[cfg(feature = "view")]
        Command::View(args) => view::run(&args),
        #[cfg(not(feature = "view"))]
        Command::View(_) => Err(missing::missing("view", "view")),
    };
    match result {
        Ok(code) => code,
        // A reader that stops early (`haphe validate ... | head`) is not an error.
        Err(error)
            if error.chain().any(|e| {
                e.downcast_ref::<std::io::Error>()
                    .is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe)
            }) =>
        {
            ExitCode::SUCCESS
        }
        Err(error) => {
            eprintln!("haphe: error: {}", message(&error));
            ExitCode::from(2)
        }
    }
}

/// The error as one line: each cause once (a cause whose text an outer message already
/// contains is not repeated), and a bare input/output error, which only writing the
/// command's own output can give (every file access names its file), named as standard
/// output's.
fn message(error: &anyhow::Error) -> String {
    if error.chain().count() == 1 && error.downcast_ref::<std::io::Error>().is_some() {
        return format!("cannot write to standard output: {error}");
    }
    let mut message = String::new();
    for cause in error.chain() {
        let text = cause.to_string();
        if message.contains(&text) {
            continue;
        }
        if !message.is_empty() {
            message.push_str(": ");
        }
        message.push_str(&text);
    }
    message
}
