//! [`model!`]: how a plugin file registers its motion model, in a few lines.

/// Declares and registers the model of one plugin file: a unit struct implementing
/// [`MotionModel`](crate::MotionModel) whose `run` is the file's own `fn run(trial: &Trial<'_>,
/// want: Want<'_>) -> Outcome`, and its [`Registration`](crate::Registration).
///
/// ```ignore
/// fn run(trial: &Trial<'_>, want: Want<'_>) -> Outcome {
///     /* ... */
/// }
///
/// crate::model! {
///     /// The driven gear as the exact solver moves it.
///     struct Push;
///     name: "push",
///     summary: "pushed by the driver's front flanks, at rest between pushes",
///     details: "The model in a few sentences.",
/// }
/// ```
macro_rules! model {
    (
        $(#[$meta:meta])*
        struct $ty:ident;
        name: $name:expr,
        summary: $summary:expr,
        details: $details:expr $(,)?
    ) => {
        $(#[$meta])*
        struct $ty;

        impl $crate::MotionModel for $ty {
            fn name(&self) -> &'static str {
                $name
            }

            fn summary(&self) -> &'static str {
                $summary
            }

            fn details(&self) -> &'static str {
                $details
            }

            fn run(&self, trial: &$crate::Trial<'_>, want: $crate::Want<'_>) -> $crate::Outcome {
                run(trial, want)
            }
        }

        inventory::submit! { $crate::Registration(&$ty) }
    };
}

pub(crate) use model;
