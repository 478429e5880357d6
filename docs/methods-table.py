#!/usr/bin/env python3
"""The table behind the method charts (docs/methods.md, "The table behind the charts"), made
from a sweep's index: one row per method and mesh, the steps side by side (`a / b`).

    python3 docs/methods-table.py docs/methods-index.csv sweeps/methods.toml > /tmp/table.md

Keys a study fixes for all its runs (its `set` and one-valued grid entries) are not in the
index: they are read from the sweep file, and a step nobody set from the scene file.
"""
import csv
import sys
import tomllib

# study: (error column, whether crossing spikes are shown)
STUDIES = {
    "strip": ("peak_err", True),
    "strip-eps": ("peak_err", True),
    "ironing": ("plateau_err", False),
    "capstan-polygon": ("analytic_err", False),
    "capstan-fillet": ("analytic_err", False),
}
MESH_KEYS = ["body.strip.mesh.elements", "body.block.mesh.elements", "body.belt.mesh.elements"]


def label(study, row):
    if study == "strip-eps":
        return f"{row['contact.enforcement']}, ε {float(row['contact.eps_n']):.1e}"
    if study == "capstan-fillet":
        return f"{row['family']}, fillet {row['rigid.drum.fillet']}"
    return row["family"]


def fixed_keys(sweep_path):
    """Per study, the keys its sweep file fixes: `set = ["key=value", …]` and grid entries
    with a single value."""
    fixed = {}
    for study in tomllib.load(open(sweep_path, "rb")).get("study", []):
        keys = dict(s.split("=", 1) for s in study.get("set", []))
        for k, values in study.get("grid", {}).items():
            if len(values) == 1:
                keys[k] = str(values[0])
        fixed[study["name"]] = keys
    return fixed


def scene_increments(scene):
    """The nominal increments of a built-in scene (`scenes/NAME.toml`)."""
    try:
        return str(tomllib.load(open(f"scenes/{scene}.toml", "rb"))["stepping"]["increments"])
    except (OSError, KeyError):
        return "—"


def mesh(row, fixed):
    for k in MESH_KEYS:
        value = row.get(k) or fixed.get(k)
        if value:
            return "×".join(v.strip() for v in value.strip("[]").split(","))
    return "—"


def error(row, column, spikes):
    if not row[column]:
        return "—"
    text = f"{100 * float(row[column]):+.2f} %"
    if spikes and row["spike_rel"] and row["status"] == "completed":
        text += f", spikes {100 * float(row['spike_rel']):.3f} %"
    return text


def outcome(row):
    if row["status"] == "completed":
        return row["failure_kind"] or "passed"
    return f"{row['failure_kind']} at {100 * float(row['load_fraction'] or 0):.0f} %"


def joined(values):
    return values[0] if all(v == values[0] for v in values) else " / ".join(values)


def main(path, sweep_path):
    rows = list(csv.DictReader(open(path, newline="")))
    fixed = fixed_keys(sweep_path)
    for study, (column, spikes) in STUDIES.items():
        groups = {}
        for r in sorted((r for r in rows if r["study"] == study), key=lambda r: int(r["ordinal"])):
            groups.setdefault((label(study, r), mesh(r, fixed.get(study, {}))), []).append(r)
        print(f"**{study}** (error: {column})\n")
        print("| method | mesh | step (increments) | error | wall time | outcome |")
        print("|---|---|---|---|---|---|")
        for (name, m), runs in groups.items():
            steps = " / ".join(
                r["stepping.increments"]
                or fixed.get(study, {}).get("stepping.increments")
                or scene_increments(r["scene"])
                for r in runs
            )
            errs = " / ".join(error(r, column, spikes) for r in runs)
            walls = " / ".join(f"{float(r['wall_time_s']):.1f} s" for r in runs)
            print(f"| {name} | {m} | {steps} | {errs} | {walls} | {joined([outcome(r) for r in runs])} |")
        print()


if __name__ == "__main__":
    args = sys.argv[1:] + ["docs/methods-index.csv", "sweeps/methods.toml"][len(sys.argv) - 1 :]
    main(args[0], args[1])
