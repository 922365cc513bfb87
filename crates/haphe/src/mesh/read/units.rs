//! The length unit of the numbers in a file.

use std::str::FromStr;

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

impl FromStr for Units {
    type Err = String;

    /// Parses `m`, `mm`, `cm`, `in` (and their long names) or a positive factor in metres
    /// per file unit such as `0.001`.
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
                _ => Err(format!(
                    "unknown unit '{s}': use m, mm, cm, in or a positive factor (metres per file unit)"
                )),
            },
        }
    }
}
