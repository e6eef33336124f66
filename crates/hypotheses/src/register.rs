//! [`hypothesis!`](crate::hypothesis): how a plugin file registers its hypothesis, in a few lines.

/// Declares and registers the hypothesis of one plugin file: a unit struct implementing
/// [`Hypothesis`](crate::Hypothesis) whose `apply` is the file's own `fn apply`, and its
/// [`Registration`](crate::Registration).
///
/// ```ignore
/// hypotheses::hypothesis! {
///     /// Every tip moved by the same angle: the whole toothing turned on its blank.
///     struct ToyShift;
///     name: "toy-shift",
///     summary: "every tip shifted by the same angle (an example plugin)",
///     params: &[SHIFT],
///     apply,
/// }
///
/// fn apply(gear: &Gear, gear_name: &str, params: &Params, _: &mut dyn RngCore) -> Manufactured {
///     /* the manufactured gear */
/// }
/// ```
///
/// `params` is a `&'static [Param]` (`&[]` for none); `details: TEXT` (the model in a few
/// sentences, what `cargo xtask help NAME` prints) may follow `summary`. `fn apply` takes what
/// [`Hypothesis::apply`](crate::Hypothesis::apply) takes after `&self`. A hypothesis that needs
/// more (its own [`Hypothesis::check`](crate::Hypothesis::check)) implements the trait by hand
/// and registers with `inventory::submit!`.
#[macro_export]
macro_rules! hypothesis {
    (
        $(#[$meta:meta])*
        struct $ty:ident;
        name: $name:expr,
        summary: $summary:expr,
        $(details: $details:expr,)?
        params: $params:expr,
        apply $(,)?
    ) => {
        $(#[$meta])*
        struct $ty;

        impl $crate::Hypothesis for $ty {
            fn name(&self) -> &'static str {
                $name
            }

            fn summary(&self) -> &'static str {
                $summary
            }

            $(
                fn details(&self) -> &'static str {
                    $details
                }
            )?

            fn params(&self) -> &'static [$crate::Param] {
                $params
            }

            fn apply(
                &self,
                gear: &$crate::geometry::Gear,
                gear_name: &str,
                params: &$crate::Params,
                rng: &mut dyn $crate::rand::RngCore,
            ) -> $crate::Manufactured {
                apply(gear, gear_name, params, rng)
            }
        }

        $crate::inventory::submit! { $crate::Registration(&$ty) }
    };
}
