//! What the page shows of the scene's force effects: a viscosity's zone (a box drawn as a
//! translucent box with its edges, an object tinted), a spring's anchor (a marker); the
//! effects that act everywhere or wherever the tool touches are named only. Textures need
//! nothing: they are felt, not seen. Sent once in the page's `/info`.

use haphe::scene::{Effect, Zone};
use serde::Serialize;

/// One effect of the scene as the page shows it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EffectMark {
    /// The kind, as a specification spells it (`viscosity`, `spring`, ...).
    pub effect: &'static str,
    /// Where it acts, as the page draws it.
    pub place: Place,
}

/// Where an effect acts, as the page draws it (JSON: `{"kind": "box", ...}`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum Place {
    /// Everywhere, or wherever the tool touches a surface: named, not drawn.
    Everywhere,
    /// Inside this box (world frame, metres): a translucent box with its edges.
    Box {
        /// The lowest corner.
        min: [f64; 3],
        /// The highest corner.
        max: [f64; 3],
    },
    /// Inside the object of this id: the object tinted.
    Object {
        /// The object's id in the scene.
        id: u32,
    },
    /// Toward this point (world frame, metres): a marker.
    Point {
        /// The point.
        at: [f64; 3],
    },
}

impl EffectMark {
    /// How the page shows `effect`.
    pub fn of(effect: &Effect) -> EffectMark {
        let place = match (effect.zone(), effect.anchor()) {
            (Some(Zone::Box { min, max }), _) => Place::Box {
                min: min.to_array(),
                max: max.to_array(),
            },
            (Some(Zone::Inside(id)), _) => Place::Object { id: id.0 },
            (_, Some(anchor)) => Place::Point {
                at: anchor.to_array(),
            },
            _ => Place::Everywhere,
        };
        EffectMark {
            effect: effect.kind(),
            place,
        }
    }
}

#[cfg(test)]
mod tests {
    use haphe::DVec3;
    use haphe::scene::ObjectId;

    use super::*;

    #[test]
    fn each_effect_is_placed_where_it_acts() {
        let (min, max) = (DVec3::new(-0.1, 0.0, 0.1), DVec3::new(0.1, 0.2, 0.3));
        for (spec, place) in [
            (
                "viscosity:2:box:-0.1:0:0.1:0.1:0.2:0.3",
                Place::Box {
                    min: min.to_array(),
                    max: max.to_array(),
                },
            ),
            ("viscosity:2:inside:7", Place::Object { id: ObjectId(7).0 }),
            (
                "spring:100:0:0:0.1",
                Place::Point {
                    at: [0.0, 0.0, 0.1],
                },
            ),
            ("viscosity:2", Place::Everywhere),
            ("vibration:150:0.3", Place::Everywhere),
            ("constant:0:0:-1", Place::Everywhere),
        ] {
            let effect: Effect = spec.parse().expect("a valid specification");
            let mark = EffectMark::of(&effect);
            assert_eq!(mark.place, place, "{spec}");
            assert_eq!(mark.effect, spec.split(':').next().unwrap_or(""));
        }
        let json = serde_json::to_value(EffectMark::of(
            &"viscosity:2:box:-0.1:0:0.1:0.1:0.2:0.3"
                .parse()
                .expect("valid"),
        ))
        .expect("serialises");
        assert_eq!(json["effect"], "viscosity");
        assert_eq!(json["place"]["kind"], "box");
        assert_eq!(json["place"]["max"][2], 0.3);
    }
}
