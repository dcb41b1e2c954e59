//! The model catalogue of the source documents: each model is a constructor from physical parameters
//! with its equations, units and source section in its doc comment, one model per file.
//!
//! Stochastic models produce a [`ModelInstance`] (a system plus the layout of its random inputs) that the
//! scenario files and the `analyze` / `simulate` commands use; every model also contributes rows to the
//! `book` report ([`crate::report::book`]).

mod instance;

pub use instance::{InputLayout, ModelInstance};

pub mod balancer_bogie;
pub mod conveyor_idler;
pub mod dynamic_stiffness_chain;
pub mod half_car;
pub mod isolation;
pub mod mine_hoist;
pub mod operator_seat;
pub mod quarter_car;
pub mod results;
pub mod scraper;
pub mod three_mass_hoist;
pub mod worked_example;
