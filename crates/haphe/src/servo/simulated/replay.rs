//! Replay of a recorded device trace: CSV lines `t,x,y,z` (seconds, metres, device frame).

use std::io::BufRead;

use glam::DVec3;

use super::behaviour::Simulated;
use super::spec::simulated_spec;
use crate::servo::device::{DeviceFault, DeviceSpec};

/// Why a HIP trace could not be read. Every variant names the file and the line (1-based).
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
    /// A line does not hold four numbers.
    #[error("{file}: line {line}: expected four numbers `t,x,y,z`, found {found:?}")]
    Malformed {
        /// The file's name as given.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The line (cut to 80 characters).
        found: String,
    },
    /// A value is not finite.
    #[error("{file}: line {line}: values must be finite")]
    NonFinite {
        /// The file's name as given.
        file: String,
        /// 1-based line number.
        line: usize,
    },
    /// A time is not later than the one before.
    #[error("{file}: line {line}: time {t} is not later than the previous sample's")]
    NotIncreasing {
        /// The file's name as given.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The time found, seconds.
        t: f64,
    },
    /// No sample at all.
    #[error("{file}: no samples (expected lines `t,x,y,z`)")]
    Empty {
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

/// A device that replays a [`HipTrace`] from its first sample: the tick at loop time `t`
/// reads the trace at `start_time + t`. It reports [`DeviceFault::Ended`] after the last
/// sample, which ends the run.
#[derive(Debug, Clone)]
pub struct ReplayDevice {
    trace: HipTrace,
    pub(super) spec: DeviceSpec,
    pub(super) open: bool,
}

impl ReplayDevice {
    /// A device replaying `trace`.
    pub fn new(trace: HipTrace) -> ReplayDevice {
        ReplayDevice {
            trace,
            spec: simulated_spec(),
            open: false,
        }
    }

    /// The trace replayed.
    pub fn trace(&self) -> &HipTrace {
        &self.trace
    }
}

impl Simulated for ReplayDevice {
    fn sample(&mut self, t: f64) -> Result<(DVec3, DVec3), DeviceFault> {
        self.trace
            .sample(self.trace.start_time() + t)
            .ok_or(DeviceFault::Ended)
    }

    /// A recorded hand does not feel the force.
    fn feel(&mut self, _force: DVec3) {}
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
}
