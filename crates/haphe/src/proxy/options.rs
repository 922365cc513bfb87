//! The proxy's options: its skin, force limit, workspace radius and tool radius, checked
//! against the table of domains.

use crate::scene::{Param, ParamError};

/// How far a probe reaches beyond the ends of a move, as a fraction of the skin: far
/// above the rounding of coordinates (about 1e-16 m per metre), well inside the skin, so a
/// stop at the skin never lands within the reach of the next probe.
pub(crate) const PROBE_REACH_OF_SKIN: f64 = 0.25;

/// Default skin, metres: how far the proxy stays off a touched surface against rounding.
/// A micrometre: far above the rounding of `f64` coordinates of a workspace of a few metres
/// (about 1e-15 m), far below what a hand can feel.
pub const DEFAULT_SKIN: f64 = 1e-6;

/// Settings of a [`Proxy`](super::Proxy), every value within its domain (see
/// [`Param`](crate::scene::Param)).
///
/// Built from [`ProxyOptions::default`] by the `with_*` builders, each of which checks its
/// value; the fields are private, so a struct literal does not build:
///
/// ```compile_fail
/// let o = haphe::proxy::ProxyOptions { skin: 1e-6, max_force: f64::NAN, workspace_radius: 1.0 };
/// ```
///
/// ```
/// # fn main() -> Result<(), haphe::scene::ParamError> {
/// use haphe::proxy::ProxyOptions;
/// let options = ProxyOptions::default().with_max_force(2.0)?.with_workspace_radius(0.5)?;
/// assert_eq!(options.max_force(), 2.0);
/// assert!(ProxyOptions::default().with_max_force(-1.0).is_err());
/// # Ok(())
/// # }
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProxyOptions {
    /// Distance kept from a touched surface, metres (see [`DEFAULT_SKIN`]).
    pub(crate) skin: f64,
    /// Largest force rendered, newtons (the device's maximum continuous force).
    pub(crate) max_force: f64,
    /// Device points farther than this from the world origin are pulled back to it,
    /// metres: keeps every product in range whatever the input.
    pub(crate) workspace_radius: f64,
    /// The tool's radius, metres: a sphere centred on the proxy (0: a point).
    pub(crate) tool_radius: f64,
}

impl Default for ProxyOptions {
    /// A micrometre of skin, [`DEFAULT_MAX_FORCE_N`](crate::scene::DEFAULT_MAX_FORCE_N)
    /// (a common desktop device), a 1 km workspace.
    fn default() -> ProxyOptions {
        ProxyOptions {
            skin: DEFAULT_SKIN,
            max_force: crate::scene::DEFAULT_MAX_FORCE_N,
            workspace_radius: 1e3,
            tool_radius: 0.0,
        }
    }
}

impl ProxyOptions {
    /// The same options with the largest force rendered, newtons.
    ///
    /// # Errors
    /// [`ParamError`] naming `max_force` outside its domain (above 0, at most
    /// `ABSURD_FORCE_N`).
    pub fn with_max_force(self, max_force: f64) -> Result<ProxyOptions, ParamError> {
        Ok(ProxyOptions {
            max_force: Param::MaxForce.check(max_force)?,
            ..self
        })
    }

    /// The same options with the skin, metres.
    ///
    /// # Errors
    /// [`ParamError`] naming `skin` outside its domain (above 0, at most a millimetre).
    pub fn with_skin(self, skin: f64) -> Result<ProxyOptions, ParamError> {
        Ok(ProxyOptions {
            skin: Param::Skin.check(skin)?,
            ..self
        })
    }

    /// The same options with the workspace radius, metres.
    ///
    /// # Errors
    /// [`ParamError`] naming `workspace_radius` outside its domain (above 0, at most
    /// `MAX_WORKSPACE_RADIUS`).
    pub fn with_workspace_radius(self, workspace_radius: f64) -> Result<ProxyOptions, ParamError> {
        Ok(ProxyOptions {
            workspace_radius: Param::WorkspaceRadius.check(workspace_radius)?,
            ..self
        })
    }

    /// The same options with the tool's radius, metres: the tool is a sphere centred on
    /// the proxy, which keeps it that far (less the skin) from every triangle. 0 (the
    /// default) is a point.
    ///
    /// # Errors
    /// [`ParamError`] naming `tool_radius` outside its domain (0 or more, at most
    /// `ABSURD_TOOL_RADIUS_M`).
    pub fn with_tool_radius(self, tool_radius: f64) -> Result<ProxyOptions, ParamError> {
        Ok(ProxyOptions {
            tool_radius: Param::ToolRadius.check(tool_radius)?,
            ..self
        })
    }

    /// The tool's radius, metres (0: a point).
    pub fn tool_radius(&self) -> f64 {
        self.tool_radius
    }

    /// Distance kept from a touched surface, metres.
    pub fn skin(&self) -> f64 {
        self.skin
    }

    /// Largest force rendered, newtons.
    pub fn max_force(&self) -> f64 {
        self.max_force
    }

    /// Device points farther than this from the world origin are pulled back to it,
    /// metres.
    pub fn workspace_radius(&self) -> f64 {
        self.workspace_radius
    }

    /// Tolerance of the constraint planes, metres: a thousandth of the skin.
    pub fn plane_tolerance(&self) -> f64 {
        self.skin * 1e-3
    }

    /// How far crossing tests reach beyond the ends of a move, metres: a quarter of the
    /// skin.
    pub fn probe_reach(&self) -> f64 {
        self.skin * PROBE_REACH_OF_SKIN
    }
}
