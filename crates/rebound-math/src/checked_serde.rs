//! `checked_serde!`: a `Deserialize` for a type whose values must pass a check, so that a deserialised value
//! is checked exactly as its constructors and setters check it (one check per type, at every door). Not part
//! of any step stage.
//!
//! The macro takes the type's definition, which derives `Serialize` as usual, and emits it unchanged beside
//! a private twin with the same fields (and field attributes: `default`, `with`) that derives serde's
//! `Deserialize` for the type (`#[serde(remote = ...)]`). The type's own `Deserialize` reads through the twin
//! and then runs the check, whose error (naming the field and the value) becomes the deserialiser's. The
//! twin lives in an anonymous `const` block, so the unchecked reader is reachable from nowhere else: unlike
//! `#[serde(remote = "Self")]` on the type itself, which would make it a public inherent function. Why not
//! `#[serde(try_from = "Raw")]`: it needs a second copy of every field written out by hand.

/// Defines a type (struct or enum, no generics) whose `serde::Deserialize` runs `$check` on what it read.
///
/// `$name` is the type's name as a string (serde's `remote` attribute needs a literal); `$check` is a
/// function `fn(Self) -> Result<Self, E>` with `E: Display` (the type's `validated`). The `Deserialize` is
/// compiled under the calling crate's `serde` feature, or always with `always` first (for a crate whose serde
/// is not optional). The type derives `Serialize` itself.
///
/// ```ignore
/// rebound_math::checked_serde! { "Rope", Rope::validated;
///     /// A rope.
///     #[cfg_attr(feature = "serde", derive(serde::Serialize))]
///     pub struct Rope { max_length: f32 }
/// }
/// ```
#[macro_export]
macro_rules! checked_serde {
    (always $name:literal, $check:expr; $(#[$meta:meta])* $vis:vis $kind:ident $ty:ident $body:tt) => {
        $(#[$meta])* $vis $kind $ty $body
        $crate::checked_serde!(@twin $name, $check; $(#[$meta])* $kind $ty $body);
    };
    ($name:literal, $check:expr; $(#[$meta:meta])* $vis:vis $kind:ident $ty:ident $body:tt) => {
        $(#[$meta])* $vis $kind $ty $body
        #[cfg(feature = "serde")]
        $crate::checked_serde!(@twin $name, $check; $(#[$meta])* $kind $ty $body);
    };
    // A type that derives serde with `#[serde(remote = "Self")]` itself (used where the derived reader must
    // see a container `#[serde(default)]`, which the twin's expansion cannot carry): `Serialize` from the
    // derived function, `Deserialize` as the derived reader and the check. The derived reader stays a public
    // inherent function, so this is for descriptions with public fields, which every door checks anyway.
    (remote_self always $ty:ty, $check:expr) => {
        $crate::checked_serde!(@impls $ty, $check);
    };
    (remote_self $ty:ty, $check:expr) => {
        #[cfg(feature = "serde")]
        $crate::checked_serde!(@impls $ty, $check);
    };
    (@impls $ty:ty, $check:expr) => {
        impl ::serde::Serialize for $ty {
            fn serialize<S: ::serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
                <$ty>::serialize(self, serializer)
            }
        }

        impl<'de> ::serde::Deserialize<'de> for $ty {
            fn deserialize<D: ::serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
                let value = <$ty>::deserialize(deserializer)?;
                ($check)(value).map_err(<D::Error as ::serde::de::Error>::custom)
            }
        }
    };
    (@twin $name:literal, $check:expr; $(#[$meta:meta])* $kind:ident $ty:ident $body:tt) => {
        #[allow(dead_code, reason = "the twin only carries the derived, unchecked reader")]
        const _: () = {
            $(#[$meta])*
            #[derive(::serde::Deserialize)]
            #[serde(remote = $name)]
            $kind Unchecked $body

            impl<'de> ::serde::Deserialize<'de> for $ty {
                fn deserialize<D: ::serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
                    let value = Unchecked::deserialize(deserializer)?;
                    ($check)(value).map_err(<D::Error as ::serde::de::Error>::custom)
                }
            }
        };
    };
}
