//! Simulated devices, so everything runs without hardware: the [`SimulatedHand`] (an arm
//! that follows a [`Trajectory`] and is pushed back by the rendered force), the
//! [`ScriptedDevice`] (follows a path exactly), the [`ReplayDevice`] (a recorded
//! [`HipTrace`]), and the scripted paths built over a scene.

mod behaviour;
mod device;
mod hand;
mod presses;
mod replay;
mod scripted;
mod spec;
mod trajectory;

pub use hand::{HandOptions, SimulatedHand};
pub use replay::ReplayDevice;
// The box of a scene's objects, for the devices' mapping.
#[doc(hidden)]
pub use scripted::scene_bounds;
pub use scripted::{PathKind, ScriptedDevice, scripted_path};
pub use spec::simulated_spec;
pub use trajectory::{Trajectory, TrajectoryError};
