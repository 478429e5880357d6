//! `--set key.path=value` on a parsed TOML table.
//!
//! Path segments walk tables by key. At an array of tables a segment may be an index
//! (`contact.0.mu`), the `name` of an element (`body.strip.material.young`), or — if it is
//! neither — the key to set in *every* element (`contact.transfer=continuous` sets the
//! scheme of all contact pairs). The value is parsed as TOML (`0.1`, `true`, `[1, 2]`,
//! `"text"`), and taken as a string when that fails (`transfer=continuous`).

use toml::{Table, Value};

/// Most segments a key path may have: scene keys are at most a few levels deep, and the walk
/// recurses once per segment.
pub const MAX_PATH_SEGMENTS: usize = 32;

/// Longest value text accepted (a value is parsed as TOML, whose nesting would recurse).
pub const MAX_VALUE_LEN: usize = 4096;

fn parse_value(raw: &str) -> Value {
    toml::from_str::<Table>(&format!("v = {raw}"))
        .ok()
        .and_then(|mut t| t.remove("v"))
        .unwrap_or_else(|| Value::String(raw.to_string()))
}

/// After the overrides, the scene's "unknown field `X`" may come from a `--set T.X.key=…`
/// meant for an entry named `X` of the array of tables `T` that has no such entry (the path
/// then set `X.key` in every entry): the message saying so, with the names `T` has.
pub fn unknown_name(root: &Table, sets: &[String], message: &str) -> Option<String> {
    let field = message.split("unknown field `").nth(1)?.split('`').next()?;
    sets.iter().find_map(|set| {
        let path = set.split_once('=')?.0.trim();
        let segs: Vec<&str> = path.split('.').collect();
        let (table, name) = (*segs.first()?, *segs.get(1)?);
        let items = root.get(table)?.as_array()?;
        if name != field || segs.len() < 3 {
            return None;
        }
        let names: Vec<&str> = items.iter().filter_map(|it| it.get("name")?.as_str()).collect();
        Some(format!(
            "`{path}`: no [[{table}]] is named `{name}` (named: {}; or give its index, {table}.0.…)",
            if names.is_empty() {
                "none".to_string()
            } else {
                names.join(", ")
            }
        ))
    })
}

/// Apply one `key.path=value` override.
pub fn apply_override(root: &mut Table, set: &str) -> Result<(), String> {
    let (path, raw) = set
        .split_once('=')
        .ok_or_else(|| "expected key.path=value".to_string())?;
    let segs: Vec<&str> = path
        .trim()
        .split('.')
        .filter(|s| !s.is_empty())
        .take(MAX_PATH_SEGMENTS + 1)
        .collect();
    if segs.is_empty() {
        return Err("empty key path".into());
    }
    if segs.len() > MAX_PATH_SEGMENTS {
        return Err(format!(
            "the key path has more than {MAX_PATH_SEGMENTS} segments; scene keys are a few levels deep"
        ));
    }
    if raw.len() > MAX_VALUE_LEN {
        return Err(format!("the value is longer than {MAX_VALUE_LEN} characters"));
    }
    if nesting(raw) > MAX_PATH_SEGMENTS {
        return Err(format!(
            "the value nests more than {MAX_PATH_SEGMENTS} arrays or tables; scene values are at most two deep"
        ));
    }
    let value = parse_value(raw.trim());
    set_in_table(root, &segs, &value, path)
}

/// Deepest nesting of brackets and braces in a value text (quotes are not special: an
/// over-estimate only refuses values no scene has).
fn nesting(raw: &str) -> usize {
    let (mut depth, mut max) = (0usize, 0usize);
    for c in raw.chars() {
        match c {
            '[' | '{' => {
                depth += 1;
                max = max.max(depth);
            }
            ']' | '}' => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    max
}

fn set_in_table(t: &mut Table, segs: &[&str], value: &Value, full: &str) -> Result<(), String> {
    let (head, rest) = (segs[0], &segs[1..]);
    if rest.is_empty() {
        t.insert(head.to_string(), value.clone());
        return Ok(());
    }
    let entry = t.entry(head.to_string()).or_insert_with(|| Value::Table(Table::new()));
    set_in_value(entry, rest, value, full)
}

fn set_in_value(v: &mut Value, segs: &[&str], value: &Value, full: &str) -> Result<(), String> {
    match v {
        Value::Table(t) => set_in_table(t, segs, value, full),
        Value::Array(items) => {
            let head = segs[0];
            if let Ok(i) = head.parse::<usize>() {
                let n = items.len();
                let item = items
                    .get_mut(i)
                    .ok_or_else(|| format!("`{full}`: index {i} out of range (array has {n})"))?;
                return if segs.len() == 1 {
                    *item = value.clone();
                    Ok(())
                } else {
                    set_in_value(item, &segs[1..], value, full)
                };
            }
            let named = items
                .iter()
                .position(|it| it.get("name").and_then(Value::as_str) == Some(head));
            if let Some(i) = named {
                if segs.len() == 1 {
                    return Err(format!("`{full}`: cannot replace the whole element `{head}`"));
                }
                return set_in_value(&mut items[i], &segs[1..], value, full);
            }
            if items.is_empty() {
                return Err(format!("`{full}`: the array is empty"));
            }
            for it in items.iter_mut() {
                set_in_value(it, segs, value, full)?;
            }
            Ok(())
        }
        _ => Err(format!("`{full}`: `{}` is not a table", segs[0])),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table() -> Table {
        toml::from_str(
            "name = \"s\"\n[stepping]\nincrements = 4\n[[contact]]\nname = \"a\"\nmu = 0.2\n[[contact]]\nname = \"b\"\nmu = 0.2\n",
        )
        .unwrap()
    }

    #[test]
    fn set_scalar_broadcast_index_and_name() {
        let mut t = table();
        apply_override(&mut t, "stepping.increments=100").unwrap();
        assert_eq!(t["stepping"]["increments"].as_integer(), Some(100));
        apply_override(&mut t, "contact.transfer=straightforward").unwrap();
        assert_eq!(t["contact"][0]["transfer"].as_str(), Some("straightforward"));
        assert_eq!(t["contact"][1]["transfer"].as_str(), Some("straightforward"));
        apply_override(&mut t, "contact.b.mu=0.3").unwrap();
        apply_override(&mut t, "contact.0.mu=0.1").unwrap();
        assert_eq!(t["contact"][0]["mu"].as_float(), Some(0.1));
        assert_eq!(t["contact"][1]["mu"].as_float(), Some(0.3));
        assert!(apply_override(&mut t, "contact.7.mu=0.1").is_err());
        assert!(apply_override(&mut t, "name.x=1").is_err());
        assert!(apply_override(&mut t, "novalue").is_err());
    }

    /// Issue 10: a key path of ~24 000 segments overflowed the stack.
    #[test]
    fn very_long_key_paths_and_deep_values_are_refused() {
        let mut t = table();
        let path = vec!["a"; 24_000].join(".");
        let e = apply_override(&mut t, &format!("{path}=1")).unwrap_err();
        assert!(e.contains("more than 32 segments"), "{e}");
        let deep = format!("stepping.increments={}1{}", "[".repeat(100_000), "]".repeat(100_000));
        assert!(apply_override(&mut t, &deep).is_err());
        let ok = vec!["a"; 32].join(".");
        apply_override(&mut t, &format!("{ok}=1")).unwrap();
        let long: Vec<String> = (0..100).map(|i| format!("[{i}.0, 0.0]")).collect();
        apply_override(&mut t, &format!("polyline=[{}]", long.join(", "))).unwrap();
    }
}
