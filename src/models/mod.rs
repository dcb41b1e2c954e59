//! The model catalogue of the source documents: each model is a constructor from physical parameters
//! with its equations, units and source section in its doc comment, one model per file.
//!
//! Stochastic models produce a [`ModelInstance`] (a system plus the layout of its random inputs) that the
//! scenario files and the `analyze` / `simulate` commands use; every model also contributes rows to the
//! `book` report ([`crate::report::book`]).

mod instance;

pub use instance::{InputLayout, ModelInstance};
pub mod dynamic_stiffness_chain;
pub mod mine_hoist;
pub mod three_mass_hoist;
