//! How an input is checked: a list of conditions, each with the field it
//! names, the value given and why that value is refused; the first that
//! does not hold is a [`Rejected`], which each crate's error turns into its
//! own `InvalidInput` variant (`?` through a `From`). No equation: one
//! shape of check that every crate above shares, so that each writes its
//! conditions once, as a table, rather than one `if` and one error a
//! condition.

/// An input that failed its check: the field, the value given and why it
/// is refused.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rejected {
    /// The field (or parameter) the input was given as.
    pub field: &'static str,
    /// The value given.
    pub value: f64,
    /// Why it is refused, and the admissible range.
    pub reason: &'static str,
}

/// One check on an input: whether it holds, then the field, the value and
/// the reason that a [`Rejected`] shows when it does not.
pub type Check = (bool, &'static str, f64, &'static str);

/// The first of `checks`, in order, that does not hold, as a [`Rejected`].
///
/// ```
/// use elcon_num::{Rejected, check};
///
/// let (low, samples) = (0.5, 2);
/// let e = check([
///     (low > 0.0, "low", low, "must be > 0"),
///     (samples >= 3, "samples", samples as f64, "at least 3 samples"),
/// ]);
/// assert_eq!(e, Err(Rejected { field: "samples", value: 2.0, reason: "at least 3 samples" }));
/// ```
pub fn check(checks: impl IntoIterator<Item = Check>) -> Result<(), Rejected> {
    match checks.into_iter().find(|c| !c.0) {
        Some((_, field, value, reason)) => Err(Rejected {
            field,
            value,
            reason,
        }),
        None => Ok(()),
    }
}

/// Implements `From<`[`Rejected`]`>` for a crate's error type whose
/// `InvalidInput { field, value, reason }` variant it becomes, so that
/// `check([...])?` returns that error.
#[macro_export]
macro_rules! rejected_into_invalid_input {
    ($error:ty) => {
        impl From<$crate::Rejected> for $error {
            fn from(r: $crate::Rejected) -> Self {
                Self::InvalidInput {
                    field: r.field,
                    value: r.value,
                    reason: r.reason,
                }
            }
        }
    };
}
