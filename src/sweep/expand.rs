//! From a plan to its runs: the list × grid expansion, a stable id per run (from the scene
//! and its overrides, so the same parameters give the same id on any machine), and the
//! deterministic `--shard i/n` split.

use super::plan::{Plan, StudyPlan};
use super::SweepError;
use std::collections::BTreeMap;

/// One run of a plan.
#[derive(Debug, Clone, PartialEq)]
pub struct PlannedRun {
    /// `STUDY-HASH` (12 hex digits of FNV-1a over the scene and the overrides).
    pub id: String,
    /// Position in the plan's expansion order (0-based).
    pub ordinal: usize,
    /// Index of the study in the plan.
    pub study: usize,
    pub scene: String,
    /// The varied parameters, `--set` key → value as written in the index.
    pub params: BTreeMap<String, String>,
    /// All overrides: the study's fixed ones, then the varied ones.
    pub sets: Vec<String>,
    /// Series name in the Pareto chart.
    pub family: String,
}

/// A `--shard i/n` selection (1-based `index`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

impl std::str::FromStr for Shard {
    type Err = String;
    fn from_str(s: &str) -> Result<Shard, String> {
        let bad = || format!("--shard {s}: expected I/N with 1 ≤ I ≤ N, e.g. --shard 2/8");
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let (index, count) = (
            i.trim().parse::<usize>().map_err(|_| bad())?,
            n.trim().parse::<usize>().map_err(|_| bad())?,
        );
        if index == 0 || count == 0 || index > count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }
}

impl Shard {
    /// Whether the run at `ordinal` belongs to this shard (round robin: neighbouring runs,
    /// often of similar cost, go to different shards).
    pub fn contains(&self, ordinal: usize) -> bool {
        ordinal % self.count == self.index - 1
    }
}

/// FNV-1a, 64 bits: stable across platforms and Rust versions (unlike `DefaultHasher`).
pub fn fnv1a(text: &str) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in text.bytes() {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

/// A TOML value as an override value (strings quoted) and as shown in the index (not).
fn render(v: &toml::Value) -> (String, String) {
    match v {
        toml::Value::String(s) => (v.to_string(), s.clone()),
        _ => {
            let t = v.to_string();
            (t.clone(), t)
        }
    }
}

fn combinations(grid: &BTreeMap<String, Vec<toml::Value>>) -> Vec<Vec<(String, toml::Value)>> {
    let mut out: Vec<Vec<(String, toml::Value)>> = vec![vec![]];
    for (k, values) in grid {
        out = out
            .into_iter()
            .flat_map(|c| {
                values.iter().map(move |v| {
                    let mut c = c.clone();
                    c.push((k.clone(), v.clone()));
                    c
                })
            })
            .collect();
    }
    out
}

fn runs_of(si: usize, s: &StudyPlan, ordinal: &mut usize) -> Vec<PlannedRun> {
    let lists: Vec<BTreeMap<String, toml::Value>> = if s.list.is_empty() {
        vec![BTreeMap::new()]
    } else {
        s.list.clone()
    };
    let mut runs = Vec::new();
    for entry in &lists {
        for combo in combinations(&s.grid) {
            let mut params = BTreeMap::new();
            let mut sets = s.set.clone();
            for (k, v) in entry.iter().map(|(k, v)| (k.clone(), v.clone())).chain(combo) {
                let (set, shown) = render(&v);
                sets.push(format!("{k}={set}"));
                params.insert(k, shown);
            }
            let family = if s.family.is_empty() {
                s.name.clone()
            } else {
                s.family
                    .iter()
                    .map(|k| params.get(k).cloned().unwrap_or_else(|| "-".into()))
                    .collect::<Vec<_>>()
                    .join(" ")
            };
            let key = std::iter::once(s.scene.as_str())
                .chain(sets.iter().map(String::as_str))
                .collect::<Vec<_>>()
                .join("\n");
            runs.push(PlannedRun {
                id: format!("{}-{:012x}", s.name, fnv1a(&key) >> 16),
                ordinal: *ordinal,
                study: si,
                scene: s.scene.clone(),
                params,
                sets,
                family,
            });
            *ordinal += 1;
        }
    }
    runs
}

/// Every run of the plan in a fixed order (studies, then list entries, then the grid with
/// the last key, in sorted order, varying fastest). Two runs with the same parameters are
/// an error.
pub fn expand(plan: &Plan) -> Result<Vec<PlannedRun>, SweepError> {
    let mut ordinal = 0;
    let runs: Vec<PlannedRun> = plan
        .studies
        .iter()
        .enumerate()
        .flat_map(|(i, s)| runs_of(i, s, &mut ordinal))
        .collect();
    let mut seen = std::collections::BTreeSet::new();
    for r in &runs {
        if !seen.insert(r.id.as_str()) {
            return Err(SweepError::Duplicate {
                id: r.id.clone(),
                sets: r.sets.join(" "),
            });
        }
    }
    Ok(runs)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    fn plan(grid: &str) -> Plan {
        let text =
            format!("name = \"t\"\n[[study]]\nscene = \"crossing\"\nset = [\"stepping.increments=20\"]\n{grid}\n");
        Plan::parse(&text, "t.toml", Path::new("")).unwrap()
    }

    #[test]
    fn grid_times_list_with_stable_ids() {
        let p = plan(
            "grid = { \"contact.transfer\" = [\"continuous\", \"straightforward\"], \"contact.eps_t\" = [1e3, 1e4, 1e5] }\n\
             list = [{ \"contact.mu\" = 0.1 }, { \"contact.mu\" = 0.3 }]",
        );
        let runs = expand(&p).unwrap();
        assert_eq!(runs.len(), 12);
        assert_eq!(runs[0].params["contact.transfer"], "continuous");
        assert_eq!(runs[0].params["contact.mu"], "0.1");
        assert_eq!(runs[1].params["contact.transfer"], "straightforward");
        assert_eq!(
            runs[1].sets,
            [
                "stepping.increments=20",
                "contact.mu=0.1",
                "contact.eps_t=1000.0",
                "contact.transfer=\"straightforward\""
            ]
        );
        assert!(runs.iter().enumerate().all(|(i, r)| r.ordinal == i));
        // ids depend on the parameters only
        let again = expand(&p).unwrap();
        assert_eq!(runs, again);
        assert!(runs[0].id.starts_with("crossing-") && runs[0].id.len() == "crossing-".len() + 12);
        assert_eq!(fnv1a("a"), 0xaf63_dc4c_8601_ec8c);
    }

    #[test]
    fn arrays_render_as_toml_and_duplicates_are_errors() {
        let p = plan("grid = { \"body.block.mesh.elements\" = [[4, 1], [8, 2]] }");
        let runs = expand(&p).unwrap();
        assert_eq!(runs[1].params["body.block.mesh.elements"], "[8, 2]");
        let p = plan("grid = { \"contact.mu\" = [0.1, 0.1] }");
        assert!(matches!(expand(&p), Err(SweepError::Duplicate { .. })));
        let p = plan("");
        assert_eq!(expand(&p).unwrap().len(), 1);
    }

    #[test]
    fn shards_partition_the_runs() {
        let s: Shard = "2/3".parse().unwrap();
        assert_eq!(s, Shard { index: 2, count: 3 });
        assert!(s.contains(1) && s.contains(4) && !s.contains(0));
        for bad in ["0/2", "3/2", "1", "a/b", "1/0"] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
        let shards: Vec<Shard> = (1..=3).map(|i| Shard { index: i, count: 3 }).collect();
        for k in 0..10 {
            assert_eq!(shards.iter().filter(|s| s.contains(k)).count(), 1);
        }
    }
}
