//! The session's CSV trace.

use std::path::Path;

use anyhow::Context;
use haphe::servo::{TickRecord, write_csv_header};

use crate::output::Staged;

/// The CSV trace writer, when asked for: a temporary file beside the target, renamed over
/// it when the run is complete (an earlier trace stays as it was if the run fails).
pub struct TraceOut {
    pub staged: Staged,
    error: Option<std::io::Error>,
}

impl TraceOut {
    pub fn create(path: &Path) -> anyhow::Result<TraceOut> {
        let mut staged = Staged::create(path)?;
        write_csv_header(staged.writer())
            .with_context(|| format!("cannot write {}", path.display()))?;
        Ok(TraceOut {
            staged,
            error: None,
        })
    }

    pub fn add(&mut self, r: &TickRecord) {
        if self.error.is_none()
            && let Err(e) = r.write_csv(self.staged.writer())
        {
            self.error = Some(e);
        }
    }

    pub fn finish(mut self) -> anyhow::Result<()> {
        if let Some(e) = self.error.take() {
            return Err(e)
                .with_context(|| format!("cannot write {}", self.staged.path().display()));
        }
        Ok(self.staged.commit()?)
    }
}
