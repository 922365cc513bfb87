//! "Did you mean": the known name closest to a misspelt one, for the messages of every
//! front end (shapes, units, devices).

/// The largest normalised Damerau–Levenshtein distance (0: equal, 1: nothing in common)
/// at which a known name is offered for a misspelt one. 0.4 offers `sphere` for `spehre`
/// (a transposition, 0.17) and `torus` for `tours`, and offers nothing for a word that
/// shares under about half its letters with every name.
pub const MAX_SUGGESTION_DISTANCE: f64 = 0.4;

/// The name of `known` closest to `given` (compared without case), when it is close
/// enough to be what was meant ([`MAX_SUGGESTION_DISTANCE`]); the first of equally close
/// names.
///
/// ```
/// use haphe::names::closest;
/// assert_eq!(closest("spehre", &["sphere", "torus"]), Some("sphere"));
/// assert_eq!(closest("cylinder", &["sphere", "torus"]), None);
/// ```
pub fn closest<'a>(given: &str, known: &[&'a str]) -> Option<&'a str> {
    let given = given.trim().to_lowercase();
    known
        .iter()
        .map(|name| {
            let d = strsim::normalized_damerau_levenshtein(&given, &name.to_lowercase());
            (1.0 - d, *name)
        })
        .filter(|(distance, _)| *distance <= MAX_SUGGESTION_DISTANCE)
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, name)| name)
}

/// `"; did you mean 'NAME'?"` for the name of `known` closest to `given`, else nothing:
/// the tail of an "unknown name" message.
pub fn did_you_mean(given: &str, known: &[&str]) -> String {
    closest(given, known).map_or_else(String::new, |name| format!("; did you mean '{name}'?"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_transposition_or_a_missing_letter_is_offered_and_an_unrelated_word_is_not() {
        let shapes = [
            "sphere",
            "torus",
            "box",
            "thin-plate",
            "concave-corner",
            "blob",
        ];
        assert_eq!(closest("spehre", &shapes), Some("sphere"));
        assert_eq!(closest("Torsu", &shapes), Some("torus"));
        assert_eq!(closest("thinplate", &shapes), Some("thin-plate"));
        assert_eq!(closest("teapot", &shapes), None);
        assert_eq!(did_you_mean("teapot", &shapes), "");
        assert_eq!(did_you_mean("blb", &shapes), "; did you mean 'blob'?");
    }
}
