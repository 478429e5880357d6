//! Numbers and counts for people: plain decimals without float noise (`11`, not
//! `1.100000e1`; `0.641364`, not `0.6413636363636566`), short lists of residuals, plurals.

/// `x` with at most `digits` significant digits, trailing zeros removed; decimal notation for
/// `1e-4 ≤ |x| < 1e6`, otherwise `1.5e-9` style. Non-finite values are `NaN`, `∞`, `-∞`.
pub fn sig(x: f64, digits: usize) -> String {
    let digits = digits.max(1);
    if x.is_nan() {
        return "NaN".into();
    }
    if x.is_infinite() {
        return if x > 0.0 { "∞".into() } else { "-∞".into() };
    }
    if x == 0.0 {
        return "0".into();
    }
    let a = x.abs();
    // the exponent after rounding to `digits` (0.99999 → 1)
    let rounded: f64 = format!("{:.*e}", digits - 1, a).parse().unwrap_or(a);
    let exp = rounded.log10().floor() as i32;
    if (-4..6).contains(&exp) {
        let decimals = (digits as i32 - 1 - exp).max(0) as usize;
        // round to `digits` significant digits also left of the point (123456 → 123000)
        trim(format!("{:.decimals$}", rounded.copysign(x)))
    } else {
        let s = format!("{:.*e}", digits - 1, x);
        match s.split_once('e') {
            Some((m, e)) => format!("{}e{e}", trim(m.to_string())),
            None => s,
        }
    }
}

fn trim(s: String) -> String {
    if s.contains('.') {
        let t = s.trim_end_matches('0').trim_end_matches('.');
        if t == "-0" {
            "0".into()
        } else {
            t.to_string()
        }
    } else {
        s
    }
}

/// `x` with up to 6 significant digits (see [`sig`]).
pub fn plain(x: f64) -> String {
    sig(x, 6)
}

/// A list of values (e.g. Newton residuals) with 3 significant digits, at most `max` of them:
/// the first three, `…`, the last ones, and how many there were.
pub fn compact_list(xs: &[f64], max: usize) -> String {
    let max = max.max(4);
    let f = |x: &f64| sig(*x, 3);
    if xs.len() <= max {
        return xs.iter().map(f).collect::<Vec<_>>().join(", ");
    }
    let tail = max - 3;
    format!(
        "{}, …, {} ({} values)",
        xs[..3].iter().map(f).collect::<Vec<_>>().join(", "),
        xs[xs.len() - tail..].iter().map(f).collect::<Vec<_>>().join(", "),
        xs.len()
    )
}

/// `n` and the noun in singular or plural: `count(1, "body", "bodies")` is `1 body`.
pub fn count(n: usize, singular: &str, plural: &str) -> String {
    format!("{n} {}", if n == 1 { singular } else { plural })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plain_numbers() {
        assert_eq!(plain(11.0), "11");
        assert_eq!(plain(0.6413636363636566), "0.641364");
        assert_eq!(plain(-0.55), "-0.55");
        assert_eq!(plain(0.0), "0");
        assert_eq!(plain(2.1e5), "210000");
        assert_eq!(plain(1.05e6), "1.05e6");
        assert_eq!(plain(3.0e-9), "3e-9");
        assert_eq!(plain(0.999_999_9), "1");
        assert_eq!(plain(f64::NAN), "NaN");
        assert_eq!(plain(f64::NEG_INFINITY), "-∞");
        assert_eq!(plain(-1e-12), "-1e-12");
        assert_eq!(sig(1.23456e-7, 3), "1.23e-7");
        assert_eq!(sig(4.9675, 3), "4.97");
        assert_eq!(sig(123456.0, 3), "123000");
    }

    #[test]
    fn compact_lists() {
        let xs: Vec<f64> = (0..31).map(|k| 10f64.powi(-k)).collect();
        let s = compact_list(&xs, 8);
        assert_eq!(s, "1, 0.1, 0.01, …, 1e-26, 1e-27, 1e-28, 1e-29, 1e-30 (31 values)");
        assert_eq!(compact_list(&[1.23456, 2.0], 8), "1.23, 2");
        assert_eq!(compact_list(&[], 8), "");
    }

    #[test]
    fn plurals() {
        assert_eq!(count(1, "body", "bodies"), "1 body");
        assert_eq!(count(0, "body", "bodies"), "0 bodies");
        assert_eq!(count(2, "slave", "slaves"), "2 slaves");
    }
}
