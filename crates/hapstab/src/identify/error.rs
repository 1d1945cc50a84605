//! What can go wrong between a recording and an identified plant: each error names the column,
//! the parameter or the problem in one line.

use thiserror::Error;

/// An identification refused or failed.
#[derive(Debug, Error)]
pub enum IdentifyError {
    /// A column of the data is missing or unusable (NaN, unsorted or non-uniform time, a
    /// constant force).
    #[error("column '{column}': {reason}")]
    Column {
        /// The column's name as the data file or the caller gives it.
        column: String,
        /// What is wrong with it.
        reason: String,
    },
    /// The data as a whole cannot be used (too few samples, an unreadable file).
    #[error("data: {0}")]
    Data(String),
    /// A model parameter given or held fixed is unusable (unknown name, non-finite or
    /// negative value).
    #[error("parameter '{name}': {reason}")]
    Parameter {
        /// The parameter's name.
        name: String,
        /// What is wrong with it.
        reason: String,
    },
    /// The model cannot explain the data: the fit did not converge, a parameter ran to the
    /// edge of the physical domain, or the fit is too poor to be reported.
    #[error("the model cannot fit the data: {0}")]
    NoFit(String),
    /// The identified or given loop is refused by the library's own checks.
    #[error(transparent)]
    Loop(#[from] crate::Error),
}

/// The result type of [`crate::identify`].
pub type IdResult<T> = std::result::Result<T, IdentifyError>;
