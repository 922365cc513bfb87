//! What a thread that changes an object's shape (a deformer, a cutter) calls with each
//! version it sends to the servo: how the view's page learns the surface it draws.

use haphe::scene::Shape;

/// Called on the changing thread with each version sent to the servo.
pub type Publish = Box<dyn FnMut(&Shape) + Send>;
