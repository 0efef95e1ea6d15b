//! A time estimate for print: two significant digits in the largest unit
//! (s, min, h) it reaches once rounded ([`TimeFigure`]), and its class
//! ([`TimeClass`]), which the rounded figure decides, so that "about 1 min"
//! is never said of a run in seconds.

/// A rough class of run time.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum TimeClass {
    /// Under a second.
    UnderASecond,
    /// Seconds (under a minute).
    Seconds,
    /// Minutes (under an hour).
    Minutes,
    /// Hours or more.
    Hours,
}

impl TimeClass {
    /// The class of `seconds`, as [`TimeFigure`] rounds them: 59.7 s is
    /// "about 1 min", in minutes.
    pub fn of(seconds: f64) -> Self {
        TimeFigure::of(seconds).class()
    }
}

impl std::fmt::Display for TimeClass {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::UnderASecond => "under a second",
            Self::Seconds => "seconds",
            Self::Minutes => "minutes",
            Self::Hours => "hours",
        })
    }
}

/// Significant digits of a printed time estimate.
const SIGNIFICANT: i32 = 2;

/// Below this many seconds a time estimate is printed as "under 0.01 s".
const SHORTEST: f64 = 0.01;

/// A unit of a printed time estimate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum TimeUnit {
    /// Seconds, below a minute.
    Second,
    /// Minutes, below an hour.
    Minute,
    /// Hours.
    Hour,
}

impl TimeUnit {
    /// Seconds in one of the unit.
    fn seconds(self) -> f64 {
        match self {
            Self::Second => 1.0,
            Self::Minute => 60.0,
            Self::Hour => 3600.0,
        }
    }

    /// The unit's symbol.
    fn symbol(self) -> &'static str {
        match self {
            Self::Second => "s",
            Self::Minute => "min",
            Self::Hour => "h",
        }
    }
}

/// A time estimate rounded for print: two significant digits in the
/// largest unit (s, min, h) it reaches once rounded, so that the figure and
/// its [`TimeClass`] agree ("about 45 s (seconds)", "about 2.3 min
/// (minutes)").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeFigure {
    /// The rounded figure in `unit`.
    value: f64,
    /// Its unit.
    unit: TimeUnit,
}

/// `x` rounded to [`SIGNIFICANT`] digits (0 and non-finite as they are).
fn significant(x: f64) -> f64 {
    if x <= 0.0 || !x.is_finite() {
        return x;
    }
    let scale = 10f64.powi(SIGNIFICANT - 1 - x.log10().floor() as i32);
    (x * scale).round() / scale
}

impl TimeFigure {
    /// `seconds` rounded (a negative or NaN count as 0, infinity as hours).
    pub fn of(seconds: f64) -> Self {
        let seconds = if seconds.is_nan() {
            0.0
        } else {
            seconds.max(0.0)
        };
        let unit = [TimeUnit::Second, TimeUnit::Minute]
            .into_iter()
            .find(|u| significant(seconds / u.seconds()) < 60.0)
            .unwrap_or(TimeUnit::Hour);
        Self {
            value: significant(seconds / unit.seconds()),
            unit,
        }
    }

    /// The rounded figure in seconds.
    pub fn seconds(&self) -> f64 {
        self.value * self.unit.seconds()
    }

    /// Its class.
    pub fn class(&self) -> TimeClass {
        match self.unit {
            TimeUnit::Second if self.value < 1.0 => TimeClass::UnderASecond,
            TimeUnit::Second => TimeClass::Seconds,
            TimeUnit::Minute => TimeClass::Minutes,
            TimeUnit::Hour => TimeClass::Hours,
        }
    }
}

impl std::fmt::Display for TimeFigure {
    /// "about 45 s", "about 2.3 min", "about 0.25 s", "under 0.01 s".
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if !self.value.is_finite() {
            return f.write_str("unbounded");
        }
        if self.unit == TimeUnit::Second && self.value < SHORTEST {
            return write!(f, "under {SHORTEST} s");
        }
        // Decimals that show SIGNIFICANT digits, none past the units.
        let decimals = (SIGNIFICANT - 1 - self.value.log10().floor() as i32).max(0) as usize;
        write!(
            f,
            "about {:.*} {}",
            decimals,
            self.value,
            self.unit.symbol()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn time_classes_follow_the_rounded_figure() {
        assert_eq!(TimeClass::of(0.5), TimeClass::UnderASecond);
        assert_eq!(TimeClass::of(59.0), TimeClass::Seconds);
        // Rounded to 60 s, printed "about 1 min": minutes, as a 140 s run is.
        assert_eq!(TimeClass::of(59.7), TimeClass::Minutes);
        assert_eq!(TimeClass::of(140.0), TimeClass::Minutes);
        assert_eq!(TimeClass::of(600.0), TimeClass::Minutes);
        assert_eq!(TimeClass::of(3599.0), TimeClass::Hours);
        assert_eq!(TimeClass::of(1e5), TimeClass::Hours);
        assert_eq!(TimeClass::Minutes.to_string(), "minutes");
        // The classes are ordered as the seconds are.
        let mut last = TimeClass::UnderASecond;
        for k in -30..60 {
            let class = TimeClass::of(1.3f64.powi(k));
            assert!(class >= last, "{k}");
            last = class;
        }
        assert_eq!(last, TimeClass::Hours);
    }

    #[test]
    fn time_figures_are_rounded_in_their_unit() {
        for (seconds, text) in [
            (0.0, "under 0.01 s"),
            (0.004, "under 0.01 s"),
            (0.2468, "about 0.25 s"),
            (4.44, "about 4.4 s"),
            (9.96, "about 10 s"),
            (44.6, "about 45 s"),
            (59.7, "about 1.0 min"),
            (140.0, "about 2.3 min"),
            (3000.0, "about 50 min"),
            (3599.0, "about 1.0 h"),
            (7.2e4, "about 20 h"),
            (f64::INFINITY, "unbounded"),
        ] {
            let figure = TimeFigure::of(seconds);
            assert_eq!(figure.to_string(), text, "{seconds}");
            assert_eq!(figure.class(), TimeClass::of(seconds), "{seconds}");
            // Within half a unit of the second significant digit.
            if seconds >= SHORTEST && seconds.is_finite() {
                let error = (figure.seconds() - seconds).abs() / seconds;
                assert!(error <= 0.05, "{seconds}: {}", figure.seconds());
            }
        }
        assert_eq!(TimeFigure::of(f64::NAN).to_string(), "under 0.01 s");
        assert_eq!(TimeFigure::of(-1.0).class(), TimeClass::UnderASecond);
    }
}
