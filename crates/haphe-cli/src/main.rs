//! The `haphe` command: a thin `main` over [`run`], which maps errors to exit codes.

mod demo;
mod generate;
mod load;
mod validate;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// haphe: real-time haptic rendering against triangle meshes.
#[derive(Parser, Debug)]
#[command(name = "haphe", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Read mesh files and report every defect with where it is.
    #[command(after_help = validate::EXIT_CODES)]
    Validate(validate::Args),
    /// Write a procedural test mesh (binary STL).
    Generate(generate::Args),
    /// A short run on built-in procedural models (no files needed).
    Demo(demo::Args),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Validate(args) => validate::run(&args),
        Command::Generate(args) => generate::run(&args),
        Command::Demo(args) => demo::run(&args),
    };
    match result {
        Ok(code) => code,
        // A reader that stops early (`haphe validate ... | head`) is not an error.
        Err(error)
            if error
                .downcast_ref::<std::io::Error>()
                .is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe) =>
        {
            ExitCode::SUCCESS
        }
        Err(error) => {
            eprintln!("haphe: error: {error:#}");
            ExitCode::from(2)
        }
    }
}
