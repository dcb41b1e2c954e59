//! The generic model kinds of scenario files: systems written out in the file rather than taken from the
//! catalogue of the source documents.

mod io;
pub mod mdof;
pub mod mdof_keys;
pub mod state_space;
pub mod transfer_function;
