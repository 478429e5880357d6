"""Interoperability check of contrail MCAP recordings with Python's `mcap` reader and
`jsonschema`: every message of every file is read and validated against its channel's
schema, the schemas must equal the checked-in files in schemas/, and the run metadata,
scene attachment and closing outcome message must be present.

Usage: python .ci/interop.py --schemas schemas FILE.mcap...
"""

import argparse
import json
import pathlib
import sys

import jsonschema
from mcap.reader import make_reader

TOPICS = {"/model", "/increment", "/iteration", "/contact", "/crossing", "/positions", "/pressure", "/log", "/outcome"}


def reject_constant(name):
    raise ValueError(f"bare JSON constant {name} (non-finite values must be strings)")


def check(path, checked_in):
    problems = []
    counts = {}
    validators = {}
    last_topic = None
    with open(path, "rb") as f:
        reader = make_reader(f)
        header = reader.get_header()
        if header.profile != "contrail":
            problems.append(f"profile {header.profile!r}, expected 'contrail'")
        summary = reader.get_summary()
        topics = {c.topic for c in summary.channels.values()}
        if topics != TOPICS:
            problems.append(f"channels {sorted(topics)}, expected {sorted(TOPICS)}")
        for schema, channel, message in reader.iter_messages(log_time_order=False):
            if schema is None or schema.encoding != "jsonschema" or channel.message_encoding != "json":
                problems.append(f"{channel.topic}: not a json channel with a jsonschema schema")
                continue
            if channel.topic not in validators:
                text = schema.data.decode()
                if text not in checked_in:
                    problems.append(f"{channel.topic}: schema {schema.name} differs from every file in schemas/")
                doc = json.loads(text)
                cls = jsonschema.validators.validator_for(doc)
                cls.check_schema(doc)
                validators[channel.topic] = cls(doc)
            try:
                value = json.loads(message.data, parse_constant=reject_constant)
            except ValueError as e:
                problems.append(f"{channel.topic} #{message.sequence}: {e}")
                continue
            errors = list(validators[channel.topic].iter_errors(value))
            if errors:
                problems.append(f"{channel.topic} #{message.sequence}: {errors[0].message}")
            counts[channel.topic] = counts.get(channel.topic, 0) + 1
            last_topic = channel.topic
        f.seek(0)
        reader = make_reader(f)
        meta = {m.name: m.metadata for m in reader.iter_metadata()}
        run = meta.get("contrail.run")
        if not run:
            problems.append("no contrail.run metadata")
        else:
            for key in ("scene", "overrides", "transfer", "parameters", "crate_version", "git_revision"):
                if key not in run:
                    problems.append(f"metadata lacks {key}")
        f.seek(0)
        reader = make_reader(f)
        attachments = [a for a in reader.iter_attachments() if a.media_type == "application/toml"]
        if not attachments or not attachments[0].data:
            problems.append("no scene attachment")
    if last_topic != "/outcome":
        problems.append(f"last message is on {last_topic}, expected /outcome")
    if counts.get("/model") != 1:
        problems.append(f"{counts.get('/model', 0)} model messages, expected 1")
    total = sum(counts.values())
    return problems, total, counts


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--schemas", required=True)
    ap.add_argument("files", nargs="+")
    args = ap.parse_args()
    checked_in = {p.read_text() for p in pathlib.Path(args.schemas).glob("*.schema.json")}
    failed = 0
    for path in args.files:
        problems, total, counts = check(path, checked_in)
        status = "ok" if not problems else "FAILED"
        print(f"{path}: {status}, {total} messages validated {counts}")
        for p in problems[:20]:
            print(f"  {p}")
        failed += bool(problems)
    print(f"mcap interop: {len(args.files) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
