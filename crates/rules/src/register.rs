//! [`rule!`]: how a plugin file registers its rule, in a few lines.

/// Declares and registers the rule of one plugin file: a unit struct implementing
/// [`EventRule`](crate::EventRule) whose `is_jam` and `is_disengagement` are the file's own
/// functions of those names, and its [`Registration`](crate::Registration).
///
/// ```ignore
/// fn is_jam(e: &Event, _: &Params) -> bool {
///     e.kind.is_contact_stop()
/// }
///
/// fn is_disengagement(e: &Event, _: &Params) -> bool {
///     e.kind == EventKind::Slip
/// }
///
/// crate::rule! {
///     /// Jams as interference; disengagement as a slip.
///     struct Mine;
///     name: "mine",
///     summary: "jam: lock, strike or blocked start; disengagement: a slip",
///     details: "The reading in a few sentences, with the sentences it rests on.",
///     params: &[MU],
///     jams: "lock, strike, blocked start",
///     disengagements: "slip",
/// }
/// ```
///
/// `params` (a `&'static [Param]`) may be left out when the rule has none.
macro_rules! rule {
    (
        $(#[$meta:meta])*
        struct $ty:ident;
        name: $name:expr,
        summary: $summary:expr,
        details: $details:expr,
        $(params: $params:expr,)?
        jams: $jams:expr,
        disengagements: $disengagements:expr $(,)?
    ) => {
        $(#[$meta])*
        struct $ty;

        impl $crate::EventRule for $ty {
            fn name(&self) -> &'static str {
                $name
            }

            fn summary(&self) -> &'static str {
                $summary
            }

            fn details(&self) -> &'static str {
                $details
            }

            $(
                fn params(&self) -> &'static [$crate::Param] {
                    $params
                }
            )?

            fn jams(&self) -> &'static str {
                $jams
            }

            fn disengagements(&self) -> &'static str {
                $disengagements
            }

            fn is_jam(&self, e: &$crate::Event, params: &$crate::Params) -> bool {
                is_jam(e, params)
            }

            fn is_disengagement(&self, e: &$crate::Event, params: &$crate::Params) -> bool {
                is_disengagement(e, params)
            }
        }

        inventory::submit! { $crate::Registration(&$ty) }
    };
}

pub(crate) use rule;
