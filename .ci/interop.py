"""Interoperability check of contrail MCAP recordings with Python's `mcap` reader and
`jsonschema`: every message of every file is read and validated against its channel's
schema, the schemas must equal the checked-in files of the recording's format (format 3:
schemas/ and schemas/foxglove/; format 2 and older: schemas/format2/), and the run metadata,
scene attachment and closing outcome message must be present. In format 3 every `/contact`,
`/pressure`, `/interface` and `/surface_contact` message is a set of equally long arrays, one `/contact` message per increment
and pair; the Foxglove channels are validated again against the schemas published in
`@foxglove/schemas` (`--foxglove DIR` with foxglove.Log.json and foxglove.SceneUpdate.json as
the package has them; the recording embeds them without their descriptions).

Usage: python .ci/interop.py --schemas schemas [--foxglove DIR] FILE.mcap...
"""

import argparse
import json
import pathlib
import sys

import jsonschema
from mcap.reader import make_reader

TOPICS = {"/model", "/increment", "/iteration", "/contact", "/crossing", "/positions", "/pressure", "/log", "/outcome"}
FOXGLOVE = {"/foxglove/log": "foxglove.Log", "/foxglove/scene": "foxglove.SceneUpdate",
            "/foxglove/reference": "foxglove.SceneUpdate"}
CONTACT_ARRAYS = ["slave", "segment", "previous_segment", "xi", "xi_anchor", "gap", "normal_force",
                  "trial_traction", "traction", "state", "crossing", "position", "contact_point",
                  "normal", "tangent", "force"]
PRESSURE_ARRAYS = ["slave", "node", "segment", "s", "contact_point", "normal_force", "tributary", "pressure"]
INTERFACE_ARRAYS = ["node", "s", "position", "normal", "tributary", "pressure", "shear", "state"]
SURFACE_ARRAYS = ["slave", "node", "facet", "previous_facet", "xi", "gap", "normal_force", "trial_traction",
                  "traction", "state", "crossing", "history_lost", "carried", "position", "contact_point",
                  "normal", "force"]


def reject_constant(name):
    raise ValueError(f"bare JSON constant {name} (non-finite values must be strings)")


def strip(doc):
    """A published schema without its descriptions and comments (as recordings embed it)."""
    if isinstance(doc, list):
        return [strip(x) for x in doc]
    if isinstance(doc, dict):
        return {k: strip(v) for k, v in doc.items() if k not in ("description", "$comment")}
    return doc


def checked_in(root, version):
    root = pathlib.Path(root)
    if version == "3":
        files = list(root.glob("*.schema.json")) + list(root.glob("foxglove/*.json"))
    else:
        files = list(root.glob("format2/*.schema.json"))
    return {p.read_text() for p in files}


class Check:
    def __init__(self, path, schemas_dir, published):
        self.path = path
        self.schemas_dir = schemas_dir
        self.published = published
        self.problems = []
        self.counts = {}
        self.validators = {}
        self.contact_per_increment = {}
        self.last_topic = None

    def run(self):
        with open(self.path, "rb") as f:
            meta = {m.name: m.metadata for m in make_reader(f).iter_metadata()}
            run = meta.get("contrail.run") or {}
            self.version = run.get("format_version", "")
            self.metadata(run)
            f.seek(0)
            reader = make_reader(f)
            if reader.get_header().profile != "contrail":
                self.problems.append(f"profile {reader.get_header().profile!r}, expected 'contrail'")
            topics = {c.topic for c in reader.get_summary().channels.values()}
            expected = TOPICS | (set(FOXGLOVE) | {"/interface", "/surface_contact"} if self.version == "3" else set())
            if topics != expected:
                self.problems.append(f"channels {sorted(topics)}, expected {sorted(expected)}")
            texts = checked_in(self.schemas_dir, self.version)
            for schema, channel, message in reader.iter_messages(log_time_order=False):
                self.message(schema, channel, message, texts)
            f.seek(0)
            attachments = [a for a in make_reader(f).iter_attachments() if a.media_type == "application/toml"]
            if not attachments or not attachments[0].data:
                self.problems.append("no scene attachment")
        if self.last_topic != "/outcome":
            self.problems.append(f"last message is on {self.last_topic}, expected /outcome")
        if self.counts.get("/model") != 1:
            self.problems.append(f"{self.counts.get('/model', 0)} model messages, expected 1")
        if self.version == "3":
            pairs = {len(v) for v in self.contact_per_increment.values()}
            if len(pairs) > 1:
                self.problems.append(f"/contact: {sorted(pairs)} messages per increment, expected one per pair")
        return self

    def metadata(self, run):
        if not run:
            self.problems.append("no contrail.run metadata")
        for key in ("scene", "overrides", "transfer", "parameters", "crate_version", "git_revision", "format_version"):
            if key not in run:
                self.problems.append(f"metadata lacks {key}")

    def validator(self, schema, channel, texts):
        text = schema.data.decode()
        if text not in texts:
            self.problems.append(f"{channel.topic}: schema {schema.name} differs from the files of format {self.version}")
        doc = json.loads(text)
        cls = jsonschema.validators.validator_for(doc)
        cls.check_schema(doc)
        validators = [cls(doc)]
        name = FOXGLOVE.get(channel.topic)
        if name:
            if schema.name != name:
                self.problems.append(f"{channel.topic}: schema name {schema.name}, expected {name}")
            full = self.published.get(name)
            if full is None:
                self.problems.append(f"{channel.topic}: no published {name} schema given (--foxglove)")
            else:
                if strip(full) != doc:
                    self.problems.append(f"{channel.topic}: embedded schema is not the published {name}")
                validators.append(jsonschema.validators.validator_for(full)(full))
        return validators

    def message(self, schema, channel, message, texts):
        topic = channel.topic
        if schema is None or schema.encoding != "jsonschema" or channel.message_encoding != "json":
            self.problems.append(f"{topic}: not a json channel with a jsonschema schema")
            return
        if topic not in self.validators:
            self.validators[topic] = self.validator(schema, channel, texts)
        try:
            value = json.loads(message.data, parse_constant=reject_constant)
        except ValueError as e:
            self.problems.append(f"{topic} #{message.sequence}: {e}")
            return
        for v in self.validators[topic]:
            errors = list(v.iter_errors(value))
            if errors:
                self.problems.append(f"{topic} #{message.sequence}: {errors[0].message}")
        if self.version == "3" and topic in ("/contact", "/pressure", "/interface", "/surface_contact"):
            fields = {"/contact": CONTACT_ARRAYS, "/pressure": PRESSURE_ARRAYS, "/interface": INTERFACE_ARRAYS,
                      "/surface_contact": SURFACE_ARRAYS}[topic]
            lengths = {k: len(value[k]) for k in fields if isinstance(value.get(k), list)}
            if len(set(lengths.values())) != 1 or len(lengths) != len(fields):
                self.problems.append(f"{topic} #{message.sequence}: arrays of lengths {lengths}")
            if topic == "/contact":
                self.contact_per_increment.setdefault(value["increment"], set()).add(value["pair"])
        self.counts[topic] = self.counts.get(topic, 0) + 1
        self.last_topic = topic


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--schemas", required=True)
    ap.add_argument("--foxglove", help="directory with the published foxglove.*.json schemas")
    ap.add_argument("files", nargs="+")
    args = ap.parse_args()
    published = {}
    if args.foxglove:
        for p in pathlib.Path(args.foxglove).glob("foxglove.*.json"):
            published[p.stem] = json.loads(p.read_text())
    failed = 0
    for path in args.files:
        c = Check(path, args.schemas, published).run()
        status = "ok" if not c.problems else "FAILED"
        total = sum(c.counts.values())
        print(f"{path}: format {c.version}, {status}, {total} messages validated {c.counts}")
        for p in c.problems[:20]:
            print(f"  {p}")
        failed += bool(c.problems)
    print(f"mcap interop: {len(args.files) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
