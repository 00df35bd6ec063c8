//! Enums whose variants are known by lower-case names.
//!
//! One macro gives each such enum its list of variants, its names, parsing,
//! `Display` and serde, so the CLI, the URL, the JSON files and the page all
//! spell a variant the same way and no surface keeps its own list.

/// An enum whose variants are known by lower-case names.
pub trait Named: Copy + 'static {
    /// Every variant's name, in declaration order.
    const NAMES: &'static [&'static str];
    /// The lower-case name.
    fn name(self) -> &'static str;
    /// The variant with this name.
    fn parse(s: &str) -> Option<Self>;
}

/// Defines `pub enum $T` with `ALL`, `NAMES`, `name()`, `parse()`,
/// [`Named`], `Display` and serde as the name.
macro_rules! named_enum {
    (
        $(#[$meta:meta])*
        pub enum $T:ident {
            $( $(#[$vmeta:meta])* $V:ident = $name:literal ),+ $(,)?
        }
    ) => {
        $(#[$meta])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum $T {
            $( $(#[$vmeta])* $V ),+
        }

        impl $T {
            /// Every variant, in declaration order.
            pub const ALL: &'static [$T] = &[$($T::$V),+];
            /// Every variant's name, in declaration order.
            pub const NAMES: &'static [&'static str] = &[$($name),+];

            /// The lower-case name.
            pub fn name(self) -> &'static str {
                match self {
                    $($T::$V => $name),+
                }
            }

            /// The variant with this name.
            pub fn parse(s: &str) -> Option<$T> {
                $T::ALL.iter().copied().find(|v| v.name() == s)
            }
        }

        impl $crate::game::named::Named for $T {
            const NAMES: &'static [&'static str] = $T::NAMES;
            fn name(self) -> &'static str {
                $T::name(self)
            }
            fn parse(s: &str) -> Option<$T> {
                $T::parse(s)
            }
        }

        impl std::fmt::Display for $T {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl serde::Serialize for $T {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.serialize_str(self.name())
            }
        }

        impl<'de> serde::Deserialize<'de> for $T {
            fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<$T, D::Error> {
                let s = String::deserialize(d)?;
                $T::parse(&s).ok_or_else(|| {
                    serde::de::Error::custom(format!(
                        "expected one of {}, got {s:?}",
                        $T::NAMES.join(", ")
                    ))
                })
            }
        }
    };
}

pub(crate) use named_enum;
