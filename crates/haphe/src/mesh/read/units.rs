//! The length unit of the numbers in a file.

use std::fmt;
use std::str::FromStr;

use glam::DVec3;

/// The length unit of the numbers in a file; haphe works in metres.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Units {
    /// The file is in metres (the default).
    #[default]
    Metres,
    /// The file is in millimetres (most CAD and 3D-printing STL files).
    Millimetres,
    /// The file is in centimetres.
    Centimetres,
    /// The file is in inches.
    Inches,
    /// Metres per file unit, finite and positive.
    Factor(f64),
}

impl Units {
    /// Metres per unit of the file.
    pub fn metres_per_unit(self) -> f64 {
        match self {
            Units::Metres => 1.0,
            Units::Millimetres => 1e-3,
            Units::Centimetres => 1e-2,
            Units::Inches => 0.0254,
            Units::Factor(f) => f,
        }
    }
}

/// The names `--units` and every front end accept for the named units (a factor is
/// also accepted), for messages.
pub const UNIT_NAMES: [&str; 4] = ["m", "mm", "cm", "in"];

impl FromStr for Units {
    type Err = String;

    /// Parses `m`, `mm`, `cm`, `in` (and their long names) or a positive factor in metres
    /// per file unit such as `0.001`. A factor that is zero or negative is refused as
    /// "must be positive"; an unknown name gets the closest known one offered.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "m" | "metre" | "metres" | "meter" | "meters" => Ok(Units::Metres),
            "mm" | "millimetre" | "millimetres" | "millimeter" | "millimeters" => {
                Ok(Units::Millimetres)
            }
            "cm" | "centimetre" | "centimetres" | "centimeter" | "centimeters" => {
                Ok(Units::Centimetres)
            }
            "in" | "inch" | "inches" => Ok(Units::Inches),
            other => match other.parse::<f64>() {
                Ok(f) if f.is_finite() && f > 0.0 => Ok(Units::Factor(f)),
                Ok(f) if f.is_finite() => Err(format!(
                    "the unit factor must be positive (metres per file unit, e.g. 0.001 for millimetres), not {s}"
                )),
                Ok(_) => Err(format!(
                    "the unit factor must be a finite positive number (metres per file unit), not {s}"
                )),
                Err(_) => {
                    const LONG: [(&str, &str); 4] = [
                        ("millimetres", "mm"),
                        ("centimetres", "cm"),
                        ("metres", "m"),
                        ("inches", "in"),
                    ];
                    let long: Vec<&str> = LONG.iter().map(|(l, _)| *l).collect();
                    let hint = crate::names::closest(other, &long)
                        .and_then(|l| LONG.iter().find(|(name, _)| *name == l))
                        .map_or_else(String::new, |(_, short)| {
                            format!(" (did you mean '{short}'?)")
                        });
                    Err(format!(
                        "unknown unit '{s}'{hint}: use m, mm, cm, in or a positive factor (metres per file unit)"
                    ))
                }
            },
        }
    }
}

impl fmt::Display for Units {
    /// The unit as `--units` takes it: `m`, `mm`, `cm`, `in`, or the factor.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Units::Metres => f.write_str("m"),
            Units::Millimetres => f.write_str("mm"),
            Units::Centimetres => f.write_str("cm"),
            Units::Inches => f.write_str("in"),
            Units::Factor(k) => write!(f, "{k}"),
        }
    }
}

/// The longest side of a bounding box above which a model is taken for one in the wrong
/// unit, metres. Desktop haptic devices reach 0.1 to 0.4 m, and the largest arm-scale
/// ones about 1 m; a model spanning more than 2 m is far more often a file in millimetres
/// (a 100 mm part read as 100 m) than a scene meant at that size.
pub const LARGEST_LIKELY_SPAN_M: f64 = 2.0;

/// The longest side of a bounding box below which a model is taken for one in the wrong
/// unit, metres: 5 mm is about the smallest feature a hand feels through a stylus, so a
/// whole model smaller than that is more often a file in metres read as millimetres.
pub const SMALLEST_LIKELY_SPAN_M: f64 = 0.005;

/// A model whose size suggests it was read in the wrong unit ([`units_hint`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnitsHint {
    /// The longest side of the model's bounding box as read, metres.
    pub span_m: f64,
    /// The unit it was read in.
    pub read_as: Units,
    /// A named unit that brings the span between 5 mm and 2 m (millimetres first, then
    /// metres, centimetres, inches), when one does.
    pub suggested: Option<Units>,
}

impl UnitsHint {
    /// The warning, with the way to give a unit spelt by `spell` (`` `--units mm` `` for
    /// the command, `` `units="mm"` `` for Python): "the model spans 100 m (its longest
    /// side, read as metres), more than the 2 m of a usual haptic scene: looks like
    /// millimetres: add `--units mm`".
    pub fn advice(&self, spell: impl Fn(Units) -> String) -> String {
        let (side, limit) = if self.span_m > LARGEST_LIKELY_SPAN_M {
            ("more", LARGEST_LIKELY_SPAN_M)
        } else {
            ("less", SMALLEST_LIKELY_SPAN_M)
        };
        let size = format!(
            "the model spans {} (its longest side, read as {}), {side} than the {} of a usual haptic scene",
            show_length(self.span_m),
            unit_name(self.read_as),
            show_length(limit)
        );
        match self.suggested {
            Some(u) => format!("{size}: looks like {}: add {}", unit_name(u), spell(u)),
            None => format!(
                "{size}: if the file is in another unit, say so as in {}",
                spell(Units::Millimetres)
            ),
        }
    }
}

/// A length for a message: metres from 1 m up, millimetres below, at most three decimals.
fn show_length(m: f64) -> String {
    let (value, unit) = if m.abs() >= 1.0 {
        (m, "m")
    } else {
        (m * 1e3, "mm")
    };
    let text = format!("{value:.3}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    format!("{text} {unit}")
}

fn unit_name(u: Units) -> String {
    match u {
        Units::Metres => "metres".into(),
        Units::Millimetres => "millimetres".into(),
        Units::Centimetres => "centimetres".into(),
        Units::Inches => "inches".into(),
        Units::Factor(k) => format!("{k} m per unit"),
    }
}

/// Whether a model whose bounding box is `lo`..`hi` (metres, as read in `units`) looks
/// read in the wrong unit: its longest side is above 2 m or below 5 mm (`haphe::mesh`'s
/// `LARGEST_LIKELY_SPAN_M` and `SMALLEST_LIKELY_SPAN_M`). The one rule of every front
/// end's units warning.
///
/// ```
/// use haphe::DVec3;
/// use haphe::mesh::{Units, units_hint};
/// // A 100 mm cube written in millimetres, read as metres: 100 m.
/// let hint = units_hint(DVec3::ZERO, DVec3::splat(100.0), Units::Metres).unwrap();
/// assert_eq!(hint.suggested, Some(Units::Millimetres));
/// assert_eq!(units_hint(DVec3::ZERO, DVec3::splat(0.1), Units::Metres), None);
/// ```
pub fn units_hint(lo: DVec3, hi: DVec3, units: Units) -> Option<UnitsHint> {
    let span_m = (hi - lo).max_element();
    let likely = |span: f64| (SMALLEST_LIKELY_SPAN_M..=LARGEST_LIKELY_SPAN_M).contains(&span);
    if !span_m.is_finite() || likely(span_m) {
        return None;
    }
    let in_file_units = span_m / units.metres_per_unit();
    let suggested = [
        Units::Millimetres,
        Units::Metres,
        Units::Centimetres,
        Units::Inches,
    ]
    .into_iter()
    .find(|u| *u != units && likely(in_file_units * u.metres_per_unit()));
    Some(UnitsHint {
        span_m,
        read_as: units,
        suggested,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube(side_m: f64, units: Units) -> Option<UnitsHint> {
        units_hint(DVec3::ZERO, DVec3::splat(side_m), units)
    }

    #[test]
    fn a_model_out_of_the_likely_spans_gets_the_unit_that_brings_it_in() {
        // A 100 mm part in millimetres read as metres, and the same read as millimetres.
        let hint = cube(100.0, Units::Metres).expect("100 m is too large");
        assert_eq!(hint.suggested, Some(Units::Millimetres));
        assert!(
            hint.advice(|u| format!("`--units {u}`"))
                .ends_with("looks like millimetres: add `--units mm`")
        );
        assert_eq!(cube(0.1, Units::Metres), None);
        assert_eq!(cube(LARGEST_LIKELY_SPAN_M, Units::Metres), None);
        assert_eq!(cube(SMALLEST_LIKELY_SPAN_M, Units::Metres), None);
        // A 0.1 m model in metres read as millimetres: 0.1 mm; metres bring it back.
        let hint = cube(1e-4, Units::Millimetres).expect("0.1 mm is too small");
        assert_eq!(hint.suggested, Some(Units::Metres));
        // 5000 file units: no named unit brings it within 5 mm to 2 m (mm gives 5 m,
        // and the larger units more).
        let hint = cube(5000.0, Units::Metres).expect("too large");
        assert_eq!(hint.suggested, None);
        assert!(
            hint.advice(|u| format!("`units=\"{u}\"`"))
                .contains("`units=\"mm\"`")
        );
        // A flat plate counts by its longest side.
        assert_eq!(
            units_hint(DVec3::ZERO, DVec3::new(0.2, 0.2, 0.0), Units::Metres),
            None
        );
    }

    #[test]
    fn factors_must_be_positive_and_names_are_suggested() {
        for bad in ["0", "-1", "-0.001"] {
            let e = bad.parse::<Units>().expect_err(bad);
            assert!(e.contains("must be positive"), "{e}");
        }
        let e = "inf".parse::<Units>().expect_err("inf");
        assert!(e.contains("finite"), "{e}");
        let e = "milimeters".parse::<Units>().expect_err("misspelt");
        assert!(e.contains("did you mean 'mm'?"), "{e}");
        for u in [
            Units::Metres,
            Units::Millimetres,
            Units::Centimetres,
            Units::Inches,
            Units::Factor(0.5),
        ] {
            assert_eq!(u.to_string().parse::<Units>(), Ok(u));
        }
    }
}
