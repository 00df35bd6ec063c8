//! Parameter machinery: what values a parameter takes, its text form, its
//! errors, and the values a configuration gives the searchers' parameters.

pub mod definition;
pub mod error;
pub mod kind;
pub mod settings;

pub use definition::Param;
pub use error::ParamError;
pub use kind::{ParamKind, Value};
pub use settings::Settings;
