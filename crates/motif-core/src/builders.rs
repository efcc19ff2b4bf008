//! The `with_*` builder methods every engine's `Params` offers.

/// Writes one `with_<field>(value) -> Self` method per listed field of a parameter struct:
///
/// ```
/// #[derive(Default)]
/// pub struct Params {
///     /// Width of the thing.
///     pub width: f64,
/// }
///
/// motif_core::builders! { Params {
///     with_width => width: f64,
/// }}
///
/// assert_eq!(Params::default().with_width(3.0).width, 3.0);
/// ```
#[macro_export]
macro_rules! builders {
    ($params:ident { $($method:ident => $field:ident: $ty:ty),* $(,)? }) => {
        impl $params {
            $(
                #[doc = concat!("Sets [`", stringify!($params), "::", stringify!($field), "`].")]
                #[must_use]
                pub fn $method(mut self, value: $ty) -> Self {
                    self.$field = value;
                    self
                }
            )*
        }
    };
}
