//! Numbers as every table and message prints them.

/// Number formatting helper used by all tables: `decimals` fixed decimals, never `-0.000`
/// (a value that rounds to zero prints without sign); non-finite values print as
/// `NaN`, `inf`, `-inf`.
pub fn fmt_f64(x: f64, decimals: usize) -> String {
    if x.is_nan() {
        return "NaN".to_owned();
    }
    let s = format!("{x:.decimals$}");
    match s.strip_prefix('-') {
        Some(rest) if rest.bytes().all(|b| b == b'0' || b == b'.') => rest.to_owned(),
        _ => s,
    }
}

/// A number for a message: as typed (`{x}`, the shortest form that reads back the same) from
/// 10^-6 to 10^12, in exponent form outside (`1e308`, never 309 digits).
pub fn fmt_number(x: f64) -> String {
    let a = x.abs();
    if !x.is_finite() || a == 0.0 || (1e-6..1e12).contains(&a) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_in_messages_stay_short() {
        assert_eq!(fmt_number(1e308), "1e308");
        assert_eq!(fmt_number(-2.5e-300), "-2.5e-300");
        assert_eq!(fmt_number(20.000000001), "20.000000001");
        assert_eq!(fmt_number(0.0), "0");
        assert_eq!(fmt_number(f64::NAN), "NaN");
    }

    #[test]
    fn fmt_f64_has_no_negative_zero() {
        assert_eq!(fmt_f64(-0.0001, 3), "0.000");
        assert_eq!(fmt_f64(-0.0, 2), "0.00");
        assert_eq!(fmt_f64(-0.4, 0), "0");
        assert_eq!(fmt_f64(-0.0006, 3), "-0.001");
        assert_eq!(fmt_f64(1.23456, 2), "1.23");
        assert_eq!(fmt_f64(-12.5, 1), "-12.5");
        assert_eq!(fmt_f64(f64::NAN, 2), "NaN");
        assert_eq!(fmt_f64(f64::INFINITY, 2), "inf");
        assert_eq!(fmt_f64(f64::NEG_INFINITY, 2), "-inf");
    }
}
