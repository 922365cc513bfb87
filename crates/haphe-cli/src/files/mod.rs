//! Every file the command reads or writes goes through here: inputs are opened once,
//! checked to be regular files (or pipes, read once as a stream) and read with a size
//! limit; outputs are written to a temporary file beside the target and renamed over it
//! only when complete. See `docs/limits-of-input.md`.

pub mod input;
pub mod output;
