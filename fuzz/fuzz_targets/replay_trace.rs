//! Fuzzes replay traces: any bytes give a trace or an error naming a line, never a panic
//! or a hang; a trace read replays with finite positions and velocities at any time.
#![no_main]

use haphe::servo::HipTrace;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let Ok(trace) = HipTrace::read("fuzz.csv", bytes) else {
        return;
    };
    assert!(!trace.is_empty());
    let (t0, t1) = (trace.start_time(), trace.end_time());
    assert!(t0.is_finite() && t1.is_finite() && t0 <= t1);
    for k in 0..=16 {
        let t = t0 + (t1 - t0) * f64::from(k) / 16.0;
        if let Some((p, v)) = trace.sample(t) {
            assert!(p.is_finite(), "position at {t}: {p}");
            assert!(!v.is_nan(), "velocity at {t}: {v}");
        }
    }
});
