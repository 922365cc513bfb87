//! Reading traces back: a device trace to replay ([`HipTrace`], CSV lines `t,x,y,z`) and
//! a trace the servo loop wrote ([`TickTrace`], the columns of [`CSV_HEADER`]). Beside
//! their writer ([`TickRecord::write_csv`](super::TickRecord::write_csv)), so that a change
//! of the columns changes both.

use std::io::BufRead;

use glam::DVec3;

use super::{CSV_HEADER, CSV_HEADER_BEFORE_BUTTONS, STATUS_NAMES};

/// Why a trace could not be read. Every variant names the file, and the line (1-based)
/// where there is one.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum TraceError {
    /// The text could not be read.
    #[error("{file}: cannot read: {source}")]
    Io {
        /// The file's name as given.
        file: String,
        /// What went wrong.
        source: std::io::Error,
    },
    /// A line of a device trace does not hold four numbers.
    #[error("{file}: line {line}: expected four numbers `t,x,y,z`, found {found:?}")]
    Malformed {
        /// The file's name as given.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The line (cut to 80 characters).
        found: String,
    },
    /// A value of a device trace is not finite.
    #[error("{file}: line {line}: values must be finite")]
    NonFinite {
        /// The file's name as given.
        file: String,
        /// 1-based line number.
        line: usize,
    },
    /// A time of a device trace is not later than the one before.
    #[error("{file}: line {line}: time {t} is not later than the previous sample's")]
    NotIncreasing {
        /// The file's name as given.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The time found, seconds.
        t: f64,
    },
    /// A device trace has no sample at all.
    #[error("{file}: no samples (expected lines `t,x,y,z`)")]
    Empty {
        /// The file's name as given.
        file: String,
    },
    /// The first line of a servo trace is not its header.
    #[error("{file}: line 1: not a haphe trace (expected the header `{CSV_HEADER}`)")]
    Header {
        /// The file's name as given.
        file: String,
    },
    /// A row of a servo trace has a bad field.
    #[error("{file}: line {line}: column {column} ({name}): {why}")]
    Field {
        /// The file's name as given.
        file: String,
        /// 1-based line number.
        line: usize,
        /// 1-based column number.
        column: usize,
        /// The column's name.
        name: &'static str,
        /// What is wrong.
        why: String,
    },
    /// A servo trace has no rows.
    #[error("{file}: the trace has no ticks")]
    NoTicks {
        /// The file's name as given.
        file: String,
    },
}

/// A recorded trace of the device point: samples `(t, p)` with strictly increasing times
/// (seconds) and positions (metres, device frame).
#[derive(Debug, Clone, PartialEq)]
pub struct HipTrace {
    times: Vec<f64>,
    points: Vec<DVec3>,
}

impl HipTrace {
    /// Reads CSV text: one sample `t,x,y,z` per line; a first line that is not numeric
    /// (a header), blank lines and lines starting with `#` are skipped. Further columns
    /// are ignored, so a trace written by the servo loop (whose first four columns are
    /// `t,hip_x,hip_y,hip_z`) replays as it is. `file` names the source in errors.
    ///
    /// # Errors
    /// [`TraceError`] naming the file and line of the first bad sample.
    pub fn read(file: &str, reader: impl BufRead) -> Result<HipTrace, TraceError> {
        let mut times = Vec::new();
        let mut points = Vec::new();
        for (i, line) in reader.lines().enumerate() {
            let line_no = i + 1;
            let line = line.map_err(|source| TraceError::Io {
                file: file.to_owned(),
                source,
            })?;
            let text = line.trim();
            if text.is_empty() || text.starts_with('#') {
                continue;
            }
            let fields: Vec<&str> = text.split(',').map(str::trim).collect();
            let numbers: Option<Vec<f64>> = fields
                .iter()
                .take(4)
                .map(|f| f.parse::<f64>().ok())
                .collect();
            let numbers = match numbers {
                Some(n) if n.len() == 4 => n,
                _ if line_no == 1 => continue,
                _ => {
                    return Err(TraceError::Malformed {
                        file: file.to_owned(),
                        line: line_no,
                        found: text.chars().take(80).collect(),
                    });
                }
            };
            if numbers.iter().any(|v| !v.is_finite()) {
                return Err(TraceError::NonFinite {
                    file: file.to_owned(),
                    line: line_no,
                });
            }
            let t = numbers[0];
            if times.last().is_some_and(|&last| t <= last) {
                return Err(TraceError::NotIncreasing {
                    file: file.to_owned(),
                    line: line_no,
                    t,
                });
            }
            times.push(t);
            points.push(DVec3::new(numbers[1], numbers[2], numbers[3]));
        }
        if times.is_empty() {
            return Err(TraceError::Empty {
                file: file.to_owned(),
            });
        }
        Ok(HipTrace { times, points })
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.times.len()
    }

    /// Whether there is no sample (never, for a trace that was read).
    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }

    /// Time of the first sample, seconds.
    pub fn start_time(&self) -> f64 {
        self.times.first().copied().unwrap_or(0.0)
    }

    /// Time of the last sample, seconds.
    pub fn end_time(&self) -> f64 {
        self.times.last().copied().unwrap_or(0.0)
    }

    /// Position (metres) and velocity (m/s) at time `t`, seconds: linear between samples;
    /// the velocity is the slope of the segment holding `t`. `None` after the last sample.
    ///
    /// # Real-time
    /// No allocation; a binary search.
    pub fn sample(&self, t: f64) -> Option<(DVec3, DVec3)> {
        let n = self.times.len();
        let first = *self.points.first()?;
        if !t.is_finite() || t > self.times[n - 1] {
            return None;
        }
        if n == 1 || t <= self.times[0] {
            return Some((first, DVec3::ZERO));
        }
        let i = self
            .times
            .partition_point(|&k| k <= t)
            .saturating_sub(1)
            .min(n - 2);
        let (t0, t1) = (self.times[i], self.times[i + 1]);
        let (p0, p1) = (self.points[i], self.points[i + 1]);
        let v = (p1 - p0) / (t1 - t0);
        if !v.is_finite() {
            // Samples closer in time than the positions' difference can be divided by
            // (a step over a few ulps): the nearer sample, at rest.
            return Some((if t - t0 <= t1 - t { p0 } else { p1 }, DVec3::ZERO));
        }
        Some((p0 + v * (t - t0), v))
    }
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
    /// Index into the trace's status names.
    pub status: u8,
    /// Penetration, metres.
    pub penetration: f64,
    /// Friction sticking.
    pub sticking: bool,
    /// Buttons held, bit 0 the first (0 in a trace written before they were recorded).
    pub buttons: u32,
    /// Whether the clutch was held.
    pub clutch: bool,
}

/// A trace the servo loop wrote ([`TickRecord::write_csv`](super::TickRecord::write_csv)),
/// read back: one row per tick, in file order.
#[derive(Debug, Clone, Default)]
pub struct TickTrace {
    /// The ticks, in file order.
    pub rows: Vec<TraceRow>,
}

impl TickTrace {
    /// Reads a trace; `file` names it in errors. A trace written before the columns
    /// `buttons` and `clutch` existed is read with no button held.
    ///
    /// # Errors
    /// [`TraceError`], naming the file, line and column.
    pub fn read(file: &str, reader: impl BufRead) -> Result<TickTrace, TraceError> {
        let mut names: Vec<&'static str> = CSV_HEADER.split(',').collect();
        let mut rows = Vec::new();
        for (i, line) in reader.lines().enumerate() {
            let line = line.map_err(|source| TraceError::Io {
                file: file.into(),
                source,
            })?;
            let line = line.trim_end_matches('\r');
            if i == 0 {
                if line == CSV_HEADER_BEFORE_BUTTONS {
                    names = CSV_HEADER_BEFORE_BUTTONS.split(',').collect();
                } else if line != CSV_HEADER {
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
            let buttons = match fields.get(16) {
                None => 0,
                Some(b) => b
                    .parse::<u32>()
                    .map_err(|_| bad(16, format!("{b:?} is not a button mask")))?,
            };
            let clutch = fields.len() > 17 && flag(17)?;
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
                buttons,
                clutch,
            });
        }
        if rows.is_empty() {
            return Err(TraceError::NoTicks { file: file.into() });
        }
        Ok(TickTrace { rows })
    }

    /// The box of every device point and proxy, metres, world frame.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        let mut points = self
            .rows
            .iter()
            .flat_map(|r| [DVec3::from_array(r.hip), DVec3::from_array(r.proxy)]);
        let first = points.next()?;
        Some(points.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_with_a_header_and_interpolates() {
        let text = "t,x,y,z\n0,0,0,0\n# note\n\n0.5,1,0,0\n1.0,1,2,0\n";
        let trace = HipTrace::read("a.csv", text.as_bytes()).expect("valid");
        assert_eq!(trace.len(), 3);
        let (p, v) = trace.sample(0.25).expect("inside");
        assert_eq!(p, DVec3::new(0.5, 0.0, 0.0));
        assert_eq!(v, DVec3::new(2.0, 0.0, 0.0));
        assert!(trace.sample(1.01).is_none());
    }

    #[test]
    fn errors_name_file_and_line() {
        let e = HipTrace::read("b.csv", "t,x,y,z\n0,0,0,0\n1,2,x,4\n".as_bytes())
            .expect_err("malformed");
        assert_eq!(
            e.to_string(),
            "b.csv: line 3: expected four numbers `t,x,y,z`, found \"1,2,x,4\""
        );
        let e = HipTrace::read("c.csv", "0,0,0,0\n0,1,1,1\n".as_bytes()).expect_err("time");
        assert!(e.to_string().starts_with("c.csv: line 2: time 0"), "{e}");
        let e = HipTrace::read("d.csv", "0,0,0,inf\n".as_bytes()).expect_err("finite");
        assert!(e.to_string().starts_with("d.csv: line 1"), "{e}");
        let e = HipTrace::read("e.csv", "t,x,y,z\n".as_bytes()).expect_err("empty");
        assert!(e.to_string().contains("no samples"), "{e}");
    }

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
            "0,0,0,0.2,0,0,0.2,0,0,0,0,,,free,0,0,0,0",
            "0.001,0,0,0.09,0,0,0.1,0,0,3,1,0,17,sticking,0.01,1,0,0",
        ]);
        let trace = TickTrace::read("t.csv", text.as_bytes()).expect("reads");
        assert_eq!(trace.rows.len(), 2);
        let r = trace.rows[1];
        assert_eq!(
            (r.object, r.triangle, r.sticking),
            (Some(0), Some(17), true)
        );
        assert_eq!(STATUS_NAMES[usize::from(r.status)], "sticking");
    }

    #[test]
    fn reads_the_buttons_and_traces_written_before_them() {
        let text = csv(&["0,0,0,0.2,0,0,0.2,0,0,0,0,,,free,0,0,5,1"]);
        let r = TickTrace::read("b.csv", text.as_bytes())
            .expect("reads")
            .rows[0];
        assert_eq!((r.buttons, r.clutch), (0b101, true));
        let old = format!("{CSV_HEADER_BEFORE_BUTTONS}\n0,0,0,0.2,0,0,0.2,0,0,0,0,,,free,0,0\n");
        let r = TickTrace::read("o.csv", old.as_bytes())
            .expect("reads")
            .rows[0];
        assert_eq!((r.buttons, r.clutch), (0, false));
        let short = format!("{CSV_HEADER}\n0,0,0,0.2,0,0,0.2,0,0,0,0,,,free,0,0\n");
        let e = TickTrace::read("s.csv", short.as_bytes()).unwrap_err();
        assert!(e.to_string().contains("16 columns, expected 18"), "{e}");
    }

    #[test]
    fn bad_files_name_the_line_and_column() {
        let e = TickTrace::read("x.csv", "t,x,y,z\n0,0,0,0\n".as_bytes()).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("x.csv: line 1: not a haphe trace"),
            "{e}"
        );
        let text = csv(&["0,0,0,0.2,0,0,0.2,0,0,nan,0,,,free,0,0,0,0"]);
        let e = TickTrace::read("x.csv", text.as_bytes()).unwrap_err();
        assert_eq!(
            e.to_string(),
            "x.csv: line 2: column 10 (force_z): NaN is not finite"
        );
        let text = csv(&["0,0,0"]);
        let e = TickTrace::read("x.csv", text.as_bytes()).unwrap_err();
        assert!(e.to_string().contains("line 2") && e.to_string().contains("3 columns"));
        let e = TickTrace::read("x.csv", csv(&[]).as_bytes()).unwrap_err();
        assert_eq!(e.to_string(), "x.csv: the trace has no ticks");
    }
}
