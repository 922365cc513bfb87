//! Trace replay: a per-tick CSV as `haphe simulate --out` writes it (columns of
//! [`CSV_HEADER`]), read once and sent to the page, which plays it with play, pause, speed
//! and a scrubber.

use std::io::BufRead;

use haphe::servo::CSV_HEADER;

/// The status names of a trace, in the order of their codes in [`Trace::encode`].
pub use haphe::servo::STATUS_NAMES;

/// Values per row in [`Trace::encode`].
pub const ROW_VALUES: usize = 15;

/// Why a trace cannot be read.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum TraceError {
    /// The file could not be read.
    #[error("{file}: {source}")]
    Io {
        /// The file.
        file: String,
        /// What failed.
        source: std::io::Error,
    },
    /// The first line is not the trace header.
    #[error("{file}: line 1: not a haphe trace (expected the header `{CSV_HEADER}`)")]
    Header {
        /// The file.
        file: String,
    },
    /// A row has a bad field.
    #[error("{file}: line {line}: column {column} ({name}): {why}")]
    Field {
        /// The file.
        file: String,
        /// Line number, from 1.
        line: usize,
        /// Column number, from 1.
        column: usize,
        /// Column name.
        name: &'static str,
        /// What is wrong.
        why: String,
    },
    /// No rows.
    #[error("{file}: the trace has no ticks")]
    Empty {
        /// The file.
        file: String,
    },
}

/// One recorded tick.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TraceRow {
    /// Time, seconds.
    pub t: f64,
    /// Device point, metres, world frame.
    pub hip: [f64; 3],
    /// Proxy, metres, world frame.
    pub proxy: [f64; 3],
    /// Force, newtons, world frame.
    pub force: [f64; 3],
    /// Object in contact.
    pub object: Option<u32>,
    /// Triangle in contact (face index of the object's file).
    pub triangle: Option<u32>,
    /// Index into [`STATUS_NAMES`].
    pub status: u8,
    /// Penetration, metres.
    pub penetration: f64,
    /// Friction sticking.
    pub sticking: bool,
}

/// A trace read from CSV.
#[derive(Debug, Clone, Default)]
pub struct Trace {
    /// The ticks, in file order.
    pub rows: Vec<TraceRow>,
}

impl Trace {
    /// Reads a trace; `file` names it in errors.
    ///
    /// # Errors
    /// [`TraceError`], naming the file, line and column.
    pub fn read(file: &str, reader: impl BufRead) -> Result<Trace, TraceError> {
        let names: Vec<&'static str> = CSV_HEADER.split(',').collect();
        let mut rows = Vec::new();
        for (i, line) in reader.lines().enumerate() {
            let line = line.map_err(|source| TraceError::Io {
                file: file.into(),
                source,
            })?;
            let line = line.trim_end_matches('\r');
            if i == 0 {
                if line != CSV_HEADER {
                    return Err(TraceError::Header { file: file.into() });
                }
                continue;
            }
            if line.is_empty() {
                continue;
            }
            let fields: Vec<&str> = line.split(',').collect();
            let bad = |column: usize, why: String| TraceError::Field {
                file: file.into(),
                line: i + 1,
                column: column + 1,
                name: names.get(column).copied().unwrap_or("extra"),
                why,
            };
            if fields.len() != names.len() {
                return Err(bad(
                    fields.len().min(names.len()),
                    format!("{} columns, expected {}", fields.len(), names.len()),
                ));
            }
            let num = |c: usize| -> Result<f64, TraceError> {
                match fields[c].parse::<f64>() {
                    Ok(v) if v.is_finite() => Ok(v),
                    Ok(v) => Err(bad(c, format!("{v} is not finite"))),
                    Err(_) => Err(bad(c, format!("{:?} is not a number", fields[c]))),
                }
            };
            let id = |c: usize| -> Result<Option<u32>, TraceError> {
                if fields[c].is_empty() {
                    Ok(None)
                } else {
                    fields[c]
                        .parse::<u32>()
                        .map(Some)
                        .map_err(|_| bad(c, format!("{:?} is not an index", fields[c])))
                }
            };
            let flag = |c: usize| -> Result<bool, TraceError> {
                match fields[c] {
                    "0" => Ok(false),
                    "1" => Ok(true),
                    other => Err(bad(c, format!("{other:?} is not 0 or 1"))),
                }
            };
            let status = STATUS_NAMES
                .iter()
                .position(|s| *s == fields[13])
                .ok_or_else(|| bad(13, format!("unknown status {:?}", fields[13])))?;
            rows.push(TraceRow {
                t: num(0)?,
                hip: [num(1)?, num(2)?, num(3)?],
                proxy: [num(4)?, num(5)?, num(6)?],
                force: [num(7)?, num(8)?, num(9)?],
                object: id(11)?,
                triangle: id(12)?,
                status: status as u8,
                penetration: num(14)?,
                sticking: flag(15)?,
            });
        }
        if rows.is_empty() {
            return Err(TraceError::Empty { file: file.into() });
        }
        Ok(Trace { rows })
    }

    /// The box of every device point and proxy, metres, world frame.
    pub fn bounds(&self) -> Option<(glam::DVec3, glam::DVec3)> {
        let mut points = self.rows.iter().flat_map(|r| {
            [
                glam::DVec3::from_array(r.hip),
                glam::DVec3::from_array(r.proxy),
            ]
        });
        let first = points.next()?;
        Some(points.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
    }

    /// The rows as little-endian f32, [`ROW_VALUES`] per row: t, HIP xyz, proxy xyz,
    /// force xyz, object (−1 when free), triangle (−1 when free), status code,
    /// penetration, sticking (0/1).
    pub fn encode(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(self.rows.len() * ROW_VALUES * 4);
        for r in &self.rows {
            let id = |v: Option<u32>| v.map_or(-1.0, |v| v as f64);
            let values = [
                r.t,
                r.hip[0],
                r.hip[1],
                r.hip[2],
                r.proxy[0],
                r.proxy[1],
                r.proxy[2],
                r.force[0],
                r.force[1],
                r.force[2],
                id(r.object),
                id(r.triangle),
                f64::from(r.status),
                r.penetration,
                f64::from(u8::from(r.sticking)),
            ];
            for v in values {
                out.extend_from_slice(&(v as f32).to_le_bytes());
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn csv(rows: &[&str]) -> String {
        let mut s = format!("{CSV_HEADER}\n");
        for r in rows {
            s.push_str(r);
            s.push('\n');
        }
        s
    }

    #[test]
    fn reads_what_the_servo_writes() {
        let text = csv(&[
            "0,0,0,0.2,0,0,0.2,0,0,0,0,,,free,0,0",
            "0.001,0,0,0.09,0,0,0.1,0,0,3,1,0,17,sticking,0.01,1",
        ]);
        let trace = Trace::read("t.csv", text.as_bytes()).expect("reads");
        assert_eq!(trace.rows.len(), 2);
        let r = trace.rows[1];
        assert_eq!(
            (r.object, r.triangle, r.sticking),
            (Some(0), Some(17), true)
        );
        assert_eq!(STATUS_NAMES[usize::from(r.status)], "sticking");
        assert_eq!(trace.encode().len(), 2 * ROW_VALUES * 4);
    }

    #[test]
    fn bad_files_name_the_line_and_column() {
        let e = Trace::read("x.csv", "t,x,y,z\n0,0,0,0\n".as_bytes()).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("x.csv: line 1: not a haphe trace"),
            "{e}"
        );
        let text = csv(&["0,0,0,0.2,0,0,0.2,0,0,nan,0,,,free,0,0"]);
        let e = Trace::read("x.csv", text.as_bytes()).unwrap_err();
        assert_eq!(
            e.to_string(),
            "x.csv: line 2: column 10 (force_z): NaN is not finite"
        );
        let text = csv(&["0,0,0"]);
        let e = Trace::read("x.csv", text.as_bytes()).unwrap_err();
        assert!(e.to_string().contains("line 2") && e.to_string().contains("3 columns"));
        let e = Trace::read("x.csv", csv(&[]).as_bytes()).unwrap_err();
        assert_eq!(e.to_string(), "x.csv: the trace has no ticks");
    }
}
