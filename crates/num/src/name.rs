//! How a name is read from a message's words: the enums of named choices
//! (a solve's method, a storage, a design's axis) parse themselves from the
//! names scenes write, and a name that is none of them is an
//! [`UnknownName`] that lists the names there are. No equation: one error
//! type and one macro ([`named!`](crate::named)) that every crate above
//! shares, so that each such enum reads, shows and (with its crate's
//! `serde` feature) serializes its names the same way.

/// A name that is none of the names of its kind: the error of parsing an
/// enum of named choices (`"fastest"` for a method). Its message names the
/// kind and lists every name there is.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UnknownName {
    /// What was parsed ("method", "storage", "axis").
    pub kind: &'static str,
    /// The name given.
    pub given: String,
    /// Every name of the kind, in the order messages list them.
    pub allowed: &'static [&'static str],
}

impl UnknownName {
    /// The error of `given`, which is none of `allowed`.
    pub fn new(kind: &'static str, given: &str, allowed: &'static [&'static str]) -> Self {
        Self {
            kind,
            given: given.to_owned(),
            allowed,
        }
    }
}

impl std::fmt::Display for UnknownName {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "unknown {} `{}`, expected one of ",
            self.kind, self.given
        )?;
        for (i, name) in self.allowed.iter().enumerate() {
            let sep = if i == 0 { "" } else { ", " };
            write!(f, "{sep}`{name}`")?;
        }
        Ok(())
    }
}

impl std::error::Error for UnknownName {}

/// Gives an enum of named choices its names' traits. The enum must have
/// `pub const ALL: [Self; N]` (every choice, in the order messages list
/// them) and `pub const fn name(self) -> &'static str`; the macro adds:
///
/// - `NAMES`, the names of `ALL` in its order;
/// - `FromStr`, whose error is an [`UnknownName`] of the `kind` given;
/// - `Display`, the name.
///
/// [`named_serde!`](crate::named_serde) adds `Serialize` and `Deserialize`.
///
/// ```
/// #[derive(Debug, Clone, Copy, PartialEq)]
/// enum Side { Left, Right }
///
/// impl Side {
///     const ALL: [Side; 2] = [Side::Left, Side::Right];
///     const fn name(self) -> &'static str {
///         match self {
///             Side::Left => "left",
///             Side::Right => "right",
///         }
///     }
/// }
///
/// elcon_num::named!(Side, "side");
///
/// assert_eq!("right".parse::<Side>(), Ok(Side::Right));
/// assert_eq!(Side::Left.to_string(), "left");
/// let e = "up".parse::<Side>().unwrap_err();
/// assert_eq!(e.to_string(), "unknown side `up`, expected one of `left`, `right`");
/// assert_eq!(e.allowed, Side::NAMES);
/// ```
#[macro_export]
macro_rules! named {
    ($ty:ident, $kind:literal) => {
        impl $ty {
            /// The names of [`ALL`](Self::ALL), in its order.
            pub const NAMES: [&'static str; $ty::ALL.len()] = {
                let mut names = [""; $ty::ALL.len()];
                let mut i = 0;
                while i < names.len() {
                    names[i] = $ty::ALL[i].name();
                    i += 1;
                }
                names
            };
        }

        impl ::std::str::FromStr for $ty {
            type Err = $crate::UnknownName;

            fn from_str(name: &str) -> ::std::result::Result<Self, Self::Err> {
                $ty::ALL
                    .into_iter()
                    .find(|choice| choice.name() == name)
                    .ok_or_else(|| $crate::UnknownName::new($kind, name, &$ty::NAMES))
            }
        }

        impl ::std::fmt::Display for $ty {
            fn fmt(&self, f: &mut ::std::fmt::Formatter<'_>) -> ::std::fmt::Result {
                f.write_str(self.name())
            }
        }
    };
}

/// `Serialize` and `Deserialize` for an enum of named choices that has
/// [`named!`](crate::named)'s traits: as its name, an unknown one serde's
/// "unknown variant" error listing `NAMES`. A crate invokes it under its
/// `serde` feature, which brings the `serde` crate
/// (`#[cfg(feature = "serde")] elcon_num::named_serde!(Method);`):
///
/// ```
/// # #[derive(Debug, Clone, Copy, PartialEq)]
/// # enum Side { Left, Right }
/// # impl Side {
/// #     const ALL: [Side; 2] = [Side::Left, Side::Right];
/// #     const fn name(self) -> &'static str {
/// #         match self { Side::Left => "left", Side::Right => "right" }
/// #     }
/// # }
/// elcon_num::named!(Side, "side");
/// elcon_num::named_serde!(Side);
///
/// assert_eq!(serde_json::to_string(&Side::Left).unwrap(), r#""left""#);
/// assert_eq!(serde_json::from_str::<Side>(r#""right""#).unwrap(), Side::Right);
/// ```
#[macro_export]
macro_rules! named_serde {
    ($ty:ident) => {
        impl ::serde::Serialize for $ty {
            fn serialize<S: ::serde::Serializer>(
                &self,
                serializer: S,
            ) -> ::std::result::Result<S::Ok, S::Error> {
                serializer.serialize_str(self.name())
            }
        }

        impl<'de> ::serde::Deserialize<'de> for $ty {
            fn deserialize<D: ::serde::Deserializer<'de>>(
                deserializer: D,
            ) -> ::std::result::Result<Self, D::Error> {
                let name =
                    <::std::string::String as ::serde::Deserialize>::deserialize(deserializer)?;
                name.parse().map_err(|_| {
                    <D::Error as ::serde::de::Error>::unknown_variant(&name, &$ty::NAMES)
                })
            }
        }
    };
}

/// The first of `all` (an enum's choices) whose name, as it shows
/// ([`Display`](std::fmt::Display)), does not parse back to it; `None`
/// when every one does, what the tests of each enum of named choices
/// assert.
pub fn unparsed<T>(all: &[T]) -> Option<T>
where
    T: Copy + PartialEq + std::fmt::Display + std::str::FromStr,
{
    all.iter()
        .copied()
        .find(|choice| choice.to_string().parse::<T>().ok() != Some(*choice))
}

/// A named choice read back from its name as a deserializer reads it (a
/// scene's TOML, a result's JSON): what [`named_serde!`](crate::named_serde)'s
/// `Deserialize` gives, without a format; an unknown name is serde's
/// "unknown variant" error. The `serde` feature.
#[cfg(feature = "serde")]
pub fn from_name<'a, T: serde::Deserialize<'a>>(
    name: &'a str,
) -> Result<T, serde::de::value::Error> {
    T::deserialize(serde::de::value::StrDeserializer::new(name))
}

#[cfg(test)]
mod tests {
    use super::UnknownName;

    #[derive(Debug, Clone, Copy, PartialEq)]
    enum Fruit {
        Apple,
        BloodOrange,
    }

    impl Fruit {
        const ALL: [Fruit; 2] = [Fruit::Apple, Fruit::BloodOrange];

        const fn name(self) -> &'static str {
            match self {
                Fruit::Apple => "apple",
                Fruit::BloodOrange => "blood-orange",
            }
        }
    }

    crate::named!(Fruit, "fruit");
    crate::named_serde!(Fruit);

    #[test]
    fn every_name_parses_back_and_an_unknown_one_lists_them() {
        assert_eq!(Fruit::NAMES, ["apple", "blood-orange"]);
        assert_eq!(super::unparsed(&Fruit::ALL), None);
        let e = "pear".parse::<Fruit>().unwrap_err();
        assert_eq!(
            e,
            UnknownName {
                kind: "fruit",
                given: "pear".into(),
                allowed: &["apple", "blood-orange"],
            }
        );
        assert_eq!(
            e.to_string(),
            "unknown fruit `pear`, expected one of `apple`, `blood-orange`"
        );
    }

    #[test]
    fn a_choice_serializes_as_its_name() {
        let json = serde_json::to_string(&[Fruit::BloodOrange, Fruit::Apple]).unwrap();
        assert_eq!(json, r#"["blood-orange","apple"]"#);
        let back: Vec<Fruit> = serde_json::from_str(&json).unwrap();
        assert_eq!(back, [Fruit::BloodOrange, Fruit::Apple]);
        let e = serde_json::from_str::<Fruit>(r#""pear""#).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("unknown variant `pear`, expected `apple` or `blood-orange`"),
            "{e}"
        );
    }
}
