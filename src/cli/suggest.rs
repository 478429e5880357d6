//! "Did you mean": the closest of a few known names to a mistyped one.

/// Edit distance with transpositions (optimal string alignment); the names are short.
pub fn distance(a: &str, b: &str) -> usize {
    let (a, b): (Vec<char>, Vec<char>) = (a.chars().collect(), b.chars().collect());
    let mut d = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, cell) in d[0].iter_mut().enumerate() {
        *cell = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut v = (d[i - 1][j - 1] + cost).min(d[i - 1][j] + 1).min(d[i][j - 1] + 1);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                v = v.min(d[i - 2][j - 2] + 1);
            }
            d[i][j] = v;
        }
    }
    d[a.len()][b.len()]
}

/// The candidate closest to `name` if it is close: at most a third of its letters (and at
/// least 1, at most 2 for short names) edited away, or `name` is a prefix of it of three
/// letters or more.
pub fn closest<'a>(name: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    candidates
        .into_iter()
        .map(|c| (distance(name, c), c))
        .filter(|(d, c)| *d <= (c.chars().count() / 3).clamp(1, 3) || (name.len() >= 3 && c.starts_with(name)))
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances() {
        assert_eq!(distance("rn", "run"), 1);
        assert_eq!(distance("strip-chanel", "strip-channel"), 1);
        assert_eq!(distance("", "abc"), 3);
        assert_eq!(distance("plto", "plot"), 1);
    }

    #[test]
    fn close_names_only() {
        let verbs = ["scenes", "run", "check", "plot", "schema", "replay", "inspect", "diff"];
        assert_eq!(closest("rn", verbs), Some("run"));
        assert_eq!(closest("inspct", verbs), Some("inspect"));
        assert_eq!(closest("plto", verbs), Some("plot"));
        assert_eq!(closest("frobnicate", verbs), None);
    }
}
