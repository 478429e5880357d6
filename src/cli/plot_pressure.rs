//! `contrail plot RUN.mcap --pressure INC`: contact pressure against arc length along the
//! master at one increment, one curve per contact pair (and run), from `/pressure`; a
//! two-pass pair is drawn as its interface (both passes combined, from `/interface`) unless
//! `--passes` asks for each pass's own profile.

use super::BadInput;
use contrail::analysis::plot::Series;
use contrail::analysis::recording::Recording;
use contrail::record::pressure::PressureRecord;

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
/// of the pair named `pair` or of every pair; `label` names the run. The two passes of a
/// two-pass pair are drawn as one curve, the interface's (named as its first pass), unless
/// `passes` (or `pair` names the second pass).
pub fn series(
    r: &Recording,
    label: &str,
    increment: Option<usize>,
    pair: Option<&str>,
    passes: bool,
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
    let joined: Vec<_> = (r.interface.iter())
        .filter(|f| !passes && f.increment == inc && pair.is_none_or(|n| n == f.name))
        .collect();
    let merged = |p: &PressureRecord| joined.iter().any(|f| p.pair == f.first_pass || p.pair == f.second_pass);
    let chosen: Vec<_> = (r.pressure.iter())
        .filter(|p| p.increment == inc && pair.is_none_or(|n| n == p.pair_name) && !merged(p))
        .collect();
    if chosen.is_empty() && joined.is_empty() {
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
    let many = chosen.len() + joined.len() > 1;
    let interfaces = joined.into_iter().map(|f| Series {
        label: if many {
            format!("{label} {} (both passes, increment {inc})", f.name)
        } else {
            format!(
                "{label} {} (both passes, increment {inc}, t = {})",
                f.name,
                contrail::format::plain(f.t)
            )
        },
        points: (f.s.iter().zip(&f.pressure))
            .map(|(s, p)| (*s, *p))
            .filter(|q| q.0.is_finite() && q.1.is_finite())
            .collect(),
        markers: Vec::new(),
    });
    Ok(interfaces
        .chain(chosen.into_iter().map(|p| {
            Series {
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
            }
        }))
        .collect())
}
