//! A number as a person writes it on a plot or in a report's caption:
//! `0`, `1487`, `0.101`, `-12.5`, `115000`, and scientific notation
//! (`2.5e-6`, `1.5e9`) only where the fixed form would need more than six
//! digits before the point or five after it.

/// The most digits the integer part of a fixed form holds (`115000`);
/// beyond them, scientific notation (`1.23e6`).
const INTEGER_DIGITS: i32 = 6;

/// The most decimals a fixed form holds, trailing zeros dropped
/// (`0.00123`, `0.0009`); beyond them, scientific notation (`1.23e-4`).
const DECIMALS: i32 = 5;

/// A number shown to a chosen resolution: its digits down to the decade
/// `10^place`, trailing zeros dropped, never `-0` or `0.0000e0`. Made by
/// [`plain`] (three significant digits) or [`plain_to`] (an axis tick).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plain {
    value: f64,
    place: i32,
    scientific: bool,
}

impl Plain {
    /// Whether it is written in fixed form (`0.101`, not `1.01e-1`).
    pub fn is_fixed(&self) -> bool {
        !self.scientific && !self.to_string().contains('e')
    }

    /// The same number in scientific notation whatever its size (`4e4`),
    /// for the ticks of an axis whose largest needs it; 0 stays `0`.
    pub fn scientific(self) -> Self {
        Self {
            scientific: true,
            ..self
        }
    }
}

/// `v` to three significant digits, its integer part whole: `1487.4` is
/// `1487`, `0.10134` is `0.101`, `2.5e-6` is `2.5e-6`, `1.5e9` is `1.5e9`.
pub fn plain(v: f64) -> Plain {
    let e = decade(v);
    let place = if e < INTEGER_DIGITS {
        (e - 2).min(0)
    } else {
        e - 2
    };
    Plain {
        value: v,
        place,
        scientific: false,
    }
}

/// `v` shown to the decade below `resolution` (an axis's tick spacing,
/// so that neighbouring ticks differ in their digits): `0.15000000000000002`
/// with ticks 0.05 apart is `0.15`, `1500` with ticks 500 apart is `1500`.
pub fn plain_to(v: f64, resolution: f64) -> Plain {
    let r = resolution.abs();
    let place = if r.is_finite() && r > 0.0 {
        decade(r) - 1
    } else {
        plain(v).place
    };
    Plain {
        value: v,
        place,
        scientific: false,
    }
}

/// The decade of `v`: `floor(log10 |v|)` (0 for 0 or a non-finite `v`).
fn decade(v: f64) -> i32 {
    let a = v.abs();
    if a > 0.0 && a.is_finite() {
        let d = a.log10().floor() as i32;
        // log10 of an exact power of ten can land a hair below it.
        if 10f64.powi(d + 1) <= a { d + 1 } else { d }
    } else {
        0
    }
}

/// `text` without the trailing zeros of its fraction (and without a
/// point left bare).
fn trimmed(text: &str) -> &str {
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.')
    } else {
        text
    }
}

impl std::fmt::Display for Plain {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let v = self.value;
        if !v.is_finite() {
            return write!(f, "{v}");
        }
        let step = 10f64.powi(self.place);
        let rounded = (v / step).round() * step;
        if rounded == 0.0 {
            return write!(f, "0");
        }
        let e = decade(rounded);
        let decimals = (-self.place).clamp(0, 300) as usize;
        let fixed = format!("{rounded:.decimals$}");
        let fixed = trimmed(&fixed);
        let shown = fixed.split_once('.').map_or(0, |(_, d)| d.len());
        if !self.scientific && e < INTEGER_DIGITS && shown <= DECIMALS as usize {
            write!(f, "{fixed}")
        } else {
            let mantissa = rounded / 10f64.powi(e);
            let decimals = (e - self.place).clamp(0, 16) as usize;
            let m = format!("{mantissa:.decimals$}");
            write!(f, "{}e{e}", trimmed(&m))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_shown_as_people_write_them() {
        for (v, shown) in [
            (0.0, "0"),
            (-0.0, "0"),
            (1487.4, "1487"),
            (1487.6, "1488"),
            (0.1013, "0.101"),
            (0.10134, "0.101"),
            (2.5e-6, "2.5e-6"),
            (1.5e9, "1.5e9"),
            (-1.5e9, "-1.5e9"),
            (-12.54, "-12.5"),
            (-0.101, "-0.101"),
            (12345.0, "12345"),
            (123456.0, "123456"),
            (1234567.0, "1.23e6"),
            (0.00123, "0.00123"),
            (0.000123, "1.23e-4"),
            (0.0009, "0.0009"),
            (0.00009, "0.00009"),
            (0.000009, "9e-6"),
            (1.0, "1"),
            (100.0, "100"),
            (2.0e-3, "0.002"),
            (f64::INFINITY, "inf"),
        ] {
            assert_eq!(plain(v).to_string(), shown, "{v}");
        }
    }

    #[test]
    fn ticks_are_shown_to_their_spacing() {
        for (v, step, shown) in [
            (0.15000000000000002, 0.05, "0.15"),
            (-0.1, 0.05, "-0.1"),
            (1e-17, 0.05, "0"),
            (-1e-17, 0.05, "0"),
            (1500.0, 500.0, "1500"),
            (1000.2, 0.1, "1000.2"),
            (0.30000000000000004, 0.1, "0.3"),
            (2.5e-6, 5e-7, "2.5e-6"),
            (1.5e9, 5e8, "1.5e9"),
            (0.004, 0.001, "0.004"),
        ] {
            assert_eq!(plain_to(v, step).to_string(), shown, "{v} by {step}");
        }
        // An axis whose largest tick needs scientific notation writes
        // every tick so.
        assert!(!plain_to(2e6, 2e5).is_fixed());
        assert_eq!(plain_to(4e5, 2e5).scientific().to_string(), "4e5");
        assert_eq!(plain_to(0.0, 2e5).scientific().to_string(), "0");
        assert!(plain(1487.0).is_fixed());
    }
}
