//! The panels of the window. Each is a function of the app's state that
//! draws; a panel the user hides is simply not called.

pub mod axes;
pub mod banner;
pub mod bifurcation;
pub mod ground;
pub mod lyapunov;
pub mod outcome_map;
pub mod params;
pub mod plots;
pub mod scene;
pub mod slider;
pub mod stack_params;
pub mod stack_scene;
