//! Simulated devices, so everything runs without hardware: the [`SimulatedHand`] (an arm
//! that follows a [`Trajectory`] and is pushed back by the rendered force), the
//! [`ScriptedDevice`] (follows a path exactly), the [`ReplayDevice`] (a recorded
//! [`HipTrace`]), and the scripted paths built over a scene.

mod device;
mod hand;
mod replay;
mod scripted;
mod trajectory;

pub use hand::{HandOptions, SimulatedHand};
pub use replay::ReplayDevice;
pub use scripted::{
    HOVER_M, PRESS_DEPTH_M, PathKind, SLIDE_SPEED, STRIKE_SPEED, ScriptedDevice, scene_bounds,
    scripted_path, simulated_spec, surface_below,
};
pub use trajectory::{Trajectory, TrajectoryError};
