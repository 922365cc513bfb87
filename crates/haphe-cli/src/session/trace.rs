//! The session's CSV trace: one row per tick; with several devices, each device's
//! columns (those of one device's trace, `t` aside) prefixed with its number, `d1_`,
//! `d2_`, ...

use std::path::Path;

use std::io::Write;

use anyhow::Context;
use haphe::servo::{CSV_HEADER, TickRecord, write_csv_header};

use crate::output::Staged;

/// The CSV trace writer, when asked for: a temporary file beside the target, renamed over
/// it when the run is complete (an earlier trace stays as it was if the run fails).
pub struct TraceOut {
    pub staged: Staged,
    error: Option<std::io::Error>,
    /// The number of devices, each with its columns.
    devices: usize,
    /// One record's line, as a single device's trace writes it.
    line: Vec<u8>,
}

/// The header of a trace of `devices` devices (of one: [`CSV_HEADER`]).
pub fn header(devices: usize) -> String {
    if devices == 1 {
        return CSV_HEADER.to_string();
    }
    let columns: Vec<&str> = CSV_HEADER.split(',').skip(1).collect();
    let mut header = String::from("t");
    for d in 1..=devices {
        for c in &columns {
            header.push_str(&format!(",d{d}_{c}"));
        }
    }
    header
}

impl TraceOut {
    /// A trace of the records of `devices` devices at `path`.
    pub fn create(path: &Path, devices: usize) -> anyhow::Result<TraceOut> {
        let mut staged = Staged::create(path)?;
        let written = if devices == 1 {
            write_csv_header(staged.writer())
        } else {
            writeln!(staged.writer(), "{}", header(devices))
        };
        written.with_context(|| format!("cannot write {}", path.display()))?;
        Ok(TraceOut {
            staged,
            error: None,
            devices,
            line: Vec::new(),
        })
    }

    /// Adds a record: a row of its own, or with several devices its device's columns of
    /// its tick's row (the records of a tick come in the devices' order).
    pub fn add(&mut self, r: &TickRecord) {
        if self.error.is_some() {
            return;
        }
        let written = if self.devices == 1 {
            r.write_csv(self.staged.writer())
        } else {
            self.add_columns(r)
        };
        if let Err(e) = written {
            self.error = Some(e);
        }
    }

    /// Writes the columns of `r` after those of the devices before it in its tick's row.
    fn add_columns(&mut self, r: &TickRecord) -> std::io::Result<()> {
        self.line.clear();
        r.write_csv(&mut self.line)?;
        let line = std::str::from_utf8(&self.line)
            .unwrap_or_default()
            .trim_end();
        // The line without its time: the tick's row starts with it once.
        let columns = line.split_once(',').map_or("", |(_, c)| c);
        let w = self.staged.writer();
        if r.device == 0 {
            write!(w, "{}", r.t)?;
        }
        write!(w, ",{columns}")?;
        if r.device as usize + 1 == self.devices {
            writeln!(w)?;
        }
        Ok(())
    }

    pub fn finish(mut self) -> anyhow::Result<()> {
        if let Some(e) = self.error.take() {
            return Err(e)
                .with_context(|| format!("cannot write {}", self.staged.path().display()));
        }
        Ok(self.staged.commit()?)
    }
}
