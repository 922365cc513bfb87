//! The clutch (indexing): while its button is held, the device moves without moving the
//! tool, so that the hand can re-centre itself in the workspace.
//!
//! While the button is held the tool (the world point given to the proxy) stays where it
//! was at the last tick before the press, at rest: the mapping's offset follows the hand,
//! `offset = tool − scale · R · p_device`, so that when the button is released the offset
//! has moved by minus the hand's travel (scaled and rotated into the world) and the tool
//! continues from where it stayed. The proxy keeps ticking against the still tool (a
//! moving object still pushes it), and the force it asks for **fades** to zero over the
//! fade time after the press and ramps back up over the same time after the release: the
//! force never jumps, stays within the proxy's maximum, and no force is rendered from the
//! hand's motion while it is held.

use glam::DVec3;

use crate::servo::device::{Buttons, DeviceMapping};

/// The clutch's state in a running servo.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Clutch {
    /// The button that holds it (bit index), none for no clutch.
    button: Option<u32>,
    /// The tool at the last tick whose tool was finite, world frame.
    last_tool: Option<DVec3>,
    /// The force's gain, 1 when released and settled, 0 when held and settled.
    gain: f64,
    /// Whether it was held at the last tick.
    held: bool,
}

impl Clutch {
    pub(super) fn new(button: Option<u32>) -> Clutch {
        Clutch {
            button,
            last_tool: None,
            gain: 1.0,
            held: false,
        }
    }

    /// Whether `buttons` hold the clutch; while it is held, moves `mapping`'s offset so that
    /// the device point `p_device` maps to the tool of the last tick.
    ///
    /// # Real-time
    /// No allocation; a few operations.
    pub(super) fn engage(
        &mut self,
        buttons: Buttons,
        p_device: DVec3,
        mapping: &mut DeviceMapping,
    ) -> bool {
        let held = self.button.is_some_and(|b| buttons.is_down(b));
        if held && let Some(tool) = self.last_tool {
            // `scale · R · p_device`: where the device point is relative to the origin.
            let reach = mapping.position_to_world(p_device) - mapping.offset();
            *mapping = mapping.with_offset(tool - reach);
        }
        self.held = held;
        held
    }

    /// Remembers the tool of this tick (a non-finite one is not kept).
    pub(super) fn remember(&mut self, tool: DVec3) {
        if tool.is_finite() {
            self.last_tool = Some(tool);
        }
    }

    /// The force's gain for this tick, moved toward 0 while held and toward 1 otherwise by
    /// `step` (the tick's period over the fade time; 1 or more: at once).
    pub(super) fn gain(&mut self, step: f64) -> f64 {
        let step = if step.is_finite() && step > 0.0 {
            step
        } else {
            1.0
        };
        let target = if self.held { 0.0 } else { 1.0 };
        self.gain = if self.gain < target {
            (self.gain + step).min(target)
        } else {
            (self.gain - step).max(target)
        };
        self.gain
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DQuat;

    #[test]
    fn held_keeps_the_tool_and_the_offset_follows_the_hand() {
        let mut mapping =
            DeviceMapping::new(DQuat::from_rotation_z(0.5), 2.0, DVec3::new(0.1, 0.2, 0.3))
                .expect("a mapping");
        let start = mapping.offset();
        let mut clutch = Clutch::new(Some(1));
        let p0 = DVec3::new(0.01, 0.0, 0.0);
        assert!(!clutch.engage(Buttons(0b01), p0, &mut mapping));
        let tool = mapping.position_to_world(p0);
        clutch.remember(tool);
        let p1 = DVec3::new(0.03, -0.02, 0.01);
        assert!(clutch.engage(Buttons(0b10), p1, &mut mapping));
        assert!(mapping.position_to_world(p1).distance(tool) < 1e-15);
        // Minus the hand's travel, scaled and rotated into the world.
        let travel = 2.0 * (DQuat::from_rotation_z(0.5) * (p1 - p0));
        assert!((mapping.offset() - start + travel).length() < 1e-15);
        assert!(!Clutch::new(None).engage(Buttons(u32::MAX), p1, &mut mapping));
    }

    #[test]
    fn the_gain_fades_and_returns_in_steps() {
        let mut clutch = Clutch::new(Some(0));
        let mut mapping = DeviceMapping::IDENTITY;
        clutch.engage(Buttons(1), DVec3::ZERO, &mut mapping);
        let gains: Vec<f64> = (0..5).map(|_| clutch.gain(0.25)).collect();
        assert_eq!(gains, [0.75, 0.5, 0.25, 0.0, 0.0]);
        clutch.engage(Buttons(0), DVec3::ZERO, &mut mapping);
        assert_eq!(clutch.gain(0.25), 0.25);
        assert_eq!(clutch.gain(f64::NAN), 1.0);
    }
}
