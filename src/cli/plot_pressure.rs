//! `contrail plot RUN.mcap --pressure INC`: contact pressure against arc length along the
//! master at one increment, one curve per contact pair (and run), from `/pressure`.

use super::BadInput;
use contrail::analysis::plot::Series;
use contrail::analysis::recording::Recording;

/// Which increment: a number or `last` (the last one with pressure profiles).
pub fn parse_increment(s: &str) -> Result<Option<usize>, String> {
    match s {
        "last" => Ok(None),
        _ => s
            .parse::<usize>()
            .map(Some)
            .map_err(|_| format!("`{s}` is not an increment number or `last`")),
    }
}

/// The pressure curves of recording `r` at `increment` (None: the last one with profiles),
/// of the pair named `pair` or of every pair; `label` names the run.
pub fn series(
    r: &Recording,
    label: &str,
    increment: Option<usize>,
    pair: Option<&str>,
) -> Result<Vec<Series>, BadInput> {
    let recorded: Vec<usize> = {
        let mut v: Vec<usize> = r.pressure.iter().map(|p| p.increment).collect();
        v.dedup();
        v
    };
    let Some(&last) = recorded.last() else {
        return Err(BadInput(format!(
            "{}: the recording has no /pressure profiles (no contact pair with node slaves, or made before the channel existed)",
            r.path
        )));
    };
    let inc = increment.unwrap_or(last);
    if !recorded.contains(&inc) {
        let near: Vec<String> = recorded.iter().rev().take(6).rev().map(|i| i.to_string()).collect();
        return Err(BadInput(format!(
            "{}: no pressure profile at increment {inc}\n  hint: profiles are written with /positions \
             (every `--positions-every` N-th increment and the last); recorded: … {}",
            r.path,
            near.join(", ")
        )));
    }
    let chosen: Vec<_> = (r.pressure.iter())
        .filter(|p| p.increment == inc && pair.is_none_or(|n| n == p.pair_name))
        .collect();
    if chosen.is_empty() {
        let names: Vec<&str> = (r.pressure.iter())
            .filter(|p| p.increment == inc)
            .map(|p| p.pair_name.as_str())
            .collect();
        return Err(BadInput(format!(
            "{}: no contact pair `{}` with a pressure profile\n  hint: pairs: {}",
            r.path,
            pair.unwrap_or(""),
            names.join(", ")
        )));
    }
    let many = chosen.len() > 1;
    Ok(chosen
        .into_iter()
        .map(|p| Series {
            label: if many {
                format!("{label} {} (increment {inc})", p.pair_name)
            } else {
                format!("{label} (increment {inc}, t = {})", contrail::format::plain(p.t))
            },
            points: p
                .points
                .iter()
                .map(|q| (q.s, q.pressure))
                .filter(|q| q.1.is_finite())
                .collect(),
            markers: Vec::new(),
        })
        .collect())
}
