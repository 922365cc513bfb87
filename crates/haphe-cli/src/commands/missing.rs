//! Commands left out of this build by its cargo features: the command still parses (with
//! whatever arguments it is given) and fails with the feature that brings it and the line
//! that builds it in, instead of clap's "unrecognized subcommand".

use std::ffi::OsString;

/// The arguments of a command this build left out: taken as they come and not read.
#[derive(clap::Args, Debug)]
#[command(disable_help_flag = true)]
pub struct Missing {
    /// Whatever followed the command.
    #[arg(num_args = 0.., trailing_var_arg = true, allow_hyphen_values = true, hide = true)]
    _args: Vec<OsString>,
}

/// The error of `haphe COMMAND` in a build without `feature`.
pub fn missing(feature: &str, command: &str) -> anyhow::Error {
    anyhow::anyhow!(
        "`haphe {command}` is not in this build: it needs the cargo feature `{feature}`. \
         Run it with `cargo run --release -p haphe-cli --features {feature} -- {command} ...`, \
         or install it with `cargo install --locked --path crates/haphe-cli --features {feature}` \
         (`--all-features` for every command)"
    )
}
