//! How a number is shown in a message: its shortest round-trip form
//! (Rust's `{}` of an f64), switched to scientific notation outside
//! `1e-4 <= |x| < 1e16` so that `1e-300` is not printed as three hundred
//! zeros; a derived quantity rounded to four digits ([`rounded`]) and a
//! count with its thousands separators ([`thousands`]). No equation: a crate of its own, below every other, so that
//! elcon-lcp and elcon-influence (which do not depend on each other) and
//! every crate above show a user's number the same way.
//!
//! Also how a name is read back from a message's words ([`UnknownName`],
//! [`named!`], [`named_serde!`] and, with the `serde` feature, `from_name`): the enums of named choices of every crate above parse,
//! show and serialize their names through it.
//!
//! And how a number is written on a plot or in a caption ([`plain`],
//! [`plain_to`]): `0`, `1487`, `0.101`, `2.5e-6`.
//!
//! And how an input is checked ([`check`]): the first of a table of
//! conditions that does not hold, a [`Rejected`] that names the field.

mod input;
mod name;
mod plain;

pub use input::{Check, Rejected, check};
#[cfg(feature = "serde")]
pub use name::from_name;
pub use name::{UnknownName, unparsed};
pub use plain::{Plain, plain, plain_to};

/// A number as a message shows it, in its shortest round-trip form: as
/// written for everyday magnitudes (`-30000000`, `0.5`), in scientific
/// notation beyond them (`1e300`, `1e-308`), so that no message holds a
/// run of hundreds of digits. Every crate above shows a user's number
/// through it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Num(pub f64);

impl std::fmt::Display for Num {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let a = self.0.abs();
        if a == 0.0 || !a.is_finite() || (1e-4..1e16).contains(&a) {
            write!(f, "{}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}

/// A derived quantity (a load centre, a distance) for a message: rounded
/// to four significant digits and shown as [`Num`] shows it (`0.013`, not
/// `0.013000000000000001`).
pub fn rounded(v: f64) -> Num {
    Num(format!("{v:.3e}").parse().unwrap_or(v))
}

/// A count with thousands separators: `1,000,000`.
pub fn thousands(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_number_is_shown_in_its_shortest_round_trip_form() {
        for (v, shown) in [
            (1e300, "1e300"),
            (-1e300, "-1e300"),
            (1e-300, "1e-300"),
            (-30e6, "-30000000"),
            (0.5, "0.5"),
            (0.0, "0"),
            (f64::INFINITY, "inf"),
            (f64::MAX, "1.7976931348623157e308"),
        ] {
            assert_eq!(Num(v).to_string(), shown);
            assert_eq!(Num(v).to_string().parse::<f64>().ok(), Some(v));
        }
        assert_eq!(Num(f64::NAN).to_string(), "NaN");
    }

    #[test]
    fn derived_quantities_keep_four_digits_and_counts_their_separators() {
        assert_eq!(rounded(0.013000000000000001).to_string(), "0.013");
        assert_eq!(rounded(123456.0).to_string(), "123500");
        assert_eq!(thousands(1_000_000), "1,000,000");
        assert_eq!(thousands(999), "999");
        assert_eq!(thousands(0), "0");
    }
}
