//! Nonlinear machines under random inputs: bump stops, asymmetric, quadratic and friction dampers, cubic
//! springs and tyres that leave the road, answered three ways.
//!
//! * Elements ([`ForceLaw`], one file per kind): [`CubicSpring`], [`BumpStop`], [`BilinearDamper`],
//!   [`QuadraticDamper`], [`CoulombFriction`], [`TyreContact`]; placed between two points of a linear
//!   model, a point and the ground, or a point and a base input ([`NonlinearElement`], [`NonlinearModel`]).
//! * Route 1 ([`linearize`]): statistical (Gaussian-equivalent) linearization with means, iterated on the
//!   linear machinery; an approximation, labelled so in every report.
//! * Route 2 ([`integrator`], [`monte_carlo`]): the nonlinear equations of motion in the time domain, driven
//!   by the same input processes as linear runs, with a symmetric splitting of exact linear flows and exact
//!   element flows; runs are HDF5 run files.
//! * Route 3 ([`WhiteNoiseOscillator`]): the exact stationary density of one degree of freedom with linear
//!   damping and nonlinear springs under white noise.
//!
//! The user documentation, with the keys of scenario files, is `docs/nonlinear.md`.

mod bilinear_damper;
mod bump_stop;
mod coulomb_friction;
mod cubic_spring;
pub mod fokker_planck;
pub mod gauss;
pub mod integrator;
mod kernel;
mod law;
pub mod linearization;
mod model;
pub mod monte_carlo;
mod quadratic_damper;
mod tyre_contact;

pub use bilinear_damper::BilinearDamper;
pub use bump_stop::{BumpStop, StopSide};
pub use coulomb_friction::CoulombFriction;
pub use cubic_spring::CubicSpring;
pub use fokker_planck::{intensity_to_density, Stationary, WhiteNoiseOscillator};
pub use kernel::Kernel;
pub use law::{ElementMoments, Equivalent, ForceLaw, Regime};
pub use linearization::{linearize, output_variance, Route1, Route1Options, Route1Outcome};
pub use model::{NonlinearElement, NonlinearModel};
pub use quadratic_damper::QuadraticDamper;
pub use tyre_contact::TyreContact;
