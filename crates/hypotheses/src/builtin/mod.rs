//! The built-in hypotheses, one file each; every file registers its own.

mod eccentric_only;
mod edmunds_split;
mod ideal;
mod measured;
mod sinusoid_only;
