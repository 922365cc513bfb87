//! [`ServoOptions`]: the settings of a servo's device — rate, proxy, mapping, ramp,
//! clutch.

use crate::proxy::ProxyOptions;
use crate::scene::{Param, ParamError};
use crate::servo::device::DeviceMapping;

/// Settings of a [`Servo`](super::Servo) (of each of its devices), every value within its
/// domain (see [`Param`]).
///
/// Built by [`ServoOptions::new`] (or [`ServoOptions::default`]) and the `with_*`
/// builders; the fields are private, so a struct literal does not build:
///
/// ```compile_fail
/// let o = haphe::servo::ServoOptions { rate_hz: 0.0, ..Default::default() };
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ServoOptions {
    /// Ticks per second, Hz, within `MIN_RATE_HZ..=MAX_RATE_HZ` (1 Hz to 40 kHz).
    pub(super) rate_hz: f64,
    /// The proxy's settings; its `max_force` is lowered to the device's if larger.
    pub(crate) proxy: ProxyOptions,
    /// Where the device workspace sits in the world.
    pub(super) mapping: DeviceMapping,
    /// Safe start: after the device point is found outside every object, the force rises
    /// linearly from zero over this time, seconds (0: at once); the clutch fades the force
    /// out and back in over the same time.
    pub(super) ramp_seconds: f64,
    /// The button that holds the clutch (bit index of [`Buttons`](crate::servo::Buttons)),
    /// none for no clutch.
    pub(super) clutch_button: Option<u32>,
}

impl Default for ServoOptions {
    /// 1 kHz, the default proxy, the identity mapping, a 50 ms ramp, no clutch.
    fn default() -> ServoOptions {
        ServoOptions {
            rate_hz: 1000.0,
            proxy: ProxyOptions::default(),
            mapping: DeviceMapping::IDENTITY,
            ramp_seconds: 0.05,
            clutch_button: None,
        }
    }
}

impl ServoOptions {
    /// The default options at `rate_hz` ticks per second.
    ///
    /// # Errors
    /// [`ParamError`] naming `rate_hz` outside `MIN_RATE_HZ..=MAX_RATE_HZ` (1 Hz to 40 kHz).
    pub fn new(rate_hz: f64) -> Result<ServoOptions, ParamError> {
        Ok(ServoOptions {
            rate_hz: Param::RateHz.check(rate_hz)?,
            ..ServoOptions::default()
        })
    }

    /// The same options with the proxy's settings.
    pub fn with_proxy(self, proxy: ProxyOptions) -> ServoOptions {
        ServoOptions { proxy, ..self }
    }

    /// The same options with the device mapping.
    pub fn with_mapping(self, mapping: DeviceMapping) -> ServoOptions {
        ServoOptions { mapping, ..self }
    }

    /// The same options with the safe start's ramp, seconds.
    ///
    /// # Errors
    /// [`ParamError`] naming `ramp_seconds` outside its domain (0 to 60 s).
    pub fn with_ramp_seconds(self, ramp_seconds: f64) -> Result<ServoOptions, ParamError> {
        Ok(ServoOptions {
            ramp_seconds: Param::RampSeconds.check(ramp_seconds)?,
            ..self
        })
    }

    /// The same options with a clutch held by the device's button `button` (0 is the
    /// first; `None`: no clutch). While it is held, the device moves without moving the
    /// tool, so the hand can re-centre itself in the workspace (the indexing of haptic
    /// toolkits):
    ///
    /// - the tool (the world point given to the proxy) stays where it was at the last tick
    ///   before the press, at rest, and the proxy stays against it;
    /// - the mapping's offset follows the hand (`offset = tool − scale · R · p_device`), so
    ///   at the release it has moved by minus the hand's travel while held, mapped into the
    ///   world, and the tool continues from where it stayed ([`Servo::mapping`](super::Servo::mapping));
    /// - the force fades linearly to zero over [`ramp_seconds`](ServoOptions::ramp_seconds)
    ///   after the press and rises back over the same time after the release: no jolt at
    ///   either, and no force from the hand's motion while held.
    ///
    /// A button beyond the 32 bits of [`Buttons`](crate::servo::Buttons) is never held.
    pub fn with_clutch_button(self, button: Option<u32>) -> ServoOptions {
        ServoOptions {
            clutch_button: button,
            ..self
        }
    }

    /// The button that holds the clutch, if any.
    pub fn clutch_button(&self) -> Option<u32> {
        self.clutch_button
    }

    /// Ticks per second, Hz.
    pub fn rate_hz(&self) -> f64 {
        self.rate_hz
    }

    /// The proxy's settings (after [`Servo::new`](super::Servo::new), with the maximum force lowered to the
    /// device's).
    pub fn proxy(&self) -> &ProxyOptions {
        &self.proxy
    }

    /// Where the device workspace sits in the world.
    pub fn mapping(&self) -> &DeviceMapping {
        &self.mapping
    }

    /// The safe start's ramp, seconds.
    pub fn ramp_seconds(&self) -> f64 {
        self.ramp_seconds
    }
}
