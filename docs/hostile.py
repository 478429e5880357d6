#!/usr/bin/env python3
"""Hostile-user measurement of the contrail binary (issue 10's done-criteria).

Mutates the built-in scenes and a small real recording, runs the binary on each with a time
limit, and counts exit codes. A scene is given to `check`; when it passes, `run --out` is
tried too (with a time limit: a run still going at the limit gets SIGINT and must then end
with 130 and a finalised recording within a grace period - a long but interruptible run is
not a hang). Damaged recordings are given to `inspect`, `diff` (against the original) and
`replay --rerun-save`.

    python3 docs/hostile.py --bin target/release/contrail --scenes 10000 --recordings 2000

Prints one line per category with the counts of exit codes; anything other than 0/1/2 (and
130 after SIGINT) or a timeout is listed with the input that caused it (kept in --keep).
"""

import argparse
import collections
import concurrent.futures as cf
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

HOSTILE = ["nan", "inf", "-inf", "-1.0", "0", "0.0", "1e308", "-9.2e18", "1e-300",
           "9223372036854775807", "18446744073709551615", "4294967296", "100000000",
           "0.5", "-1", '""', "[]", "[0.0]", "[nan, 0.0]", "[[0.0, 0.0]]",
           "[[0.0, 0.0], [0.0, 0.0]]", "{}", "true"]
TOKENS = ['[[rigid]]\nname = "C"\npoint = [0.0, 0.0]\n', '[[contact]]\nname = "base"\n',
          "[[body]]\n", "arc = { centre = [0.0, 1.0], radius = inf, from_deg = -30.0, to_deg = -150.0 }\n",
          "[", "]", '"', "=", "\n", ",", "#", "{", "}", "'", "\\"]
NUM = re.compile(rb"(?<![A-Za-z0-9_])-?\d[\d.eE+-]*")


def mutate_scene(text: bytes, rng: random.Random) -> bytes:
    t = bytearray(text)
    for _ in range(rng.randint(1, 5)):
        kind = rng.choices(["num", "ins", "del", "dup", "byte"], [4, 1, 1, 1, 1])[0]
        n = max(len(t), 1)
        if kind == "num":
            nums = list(NUM.finditer(bytes(t)))
            if nums:
                m = rng.choice(nums)
                t[m.start():m.end()] = rng.choice(HOSTILE).encode()
        elif kind == "ins":
            at = rng.randint(0, len(t))
            t[at:at] = rng.choice(TOKENS).encode()
        elif kind == "del":
            at = rng.randrange(n)
            del t[at:at + rng.randint(1, 40)]
        elif kind == "dup":
            at = rng.randrange(n)
            t[at:at] = t[at:at + rng.randint(1, 200)]
        elif t:
            t[rng.randrange(len(t))] = rng.randint(32, 126)
    return bytes(t)


def damage_recording(good: bytes, rng: random.Random) -> bytes:
    b = bytearray(good)
    kind = rng.choice(["flip", "trunc", "zero", "junk", "multi"])
    if kind == "flip":
        b[rng.randrange(8, len(b))] ^= rng.randint(1, 255)
    elif kind == "trunc":
        b = b[:rng.randrange(len(b))]
    elif kind == "zero":
        at = rng.randrange(8, len(b))
        end = min(at + rng.randint(1, 64), len(b))
        b[at:end] = bytes(end - at)
    elif kind == "junk":
        b += bytes(rng.randrange(256) for _ in range(rng.randint(1, 64)))
    else:
        for _ in range(rng.randint(2, 16)):
            b[rng.randrange(8, len(b))] ^= rng.randint(1, 255)
    return bytes(b)


def call(args, timeout, grace=10):
    """(exit code or 'timeout'/'signal N', seconds, stderr tail)."""
    t0 = time.monotonic()
    p = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    try:
        _, err = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        p.send_signal(signal.SIGINT)
        try:
            _, err = p.communicate(timeout=grace)
            code = p.returncode
            return ("sigint->%s" % code, time.monotonic() - t0, err[-300:])
        except subprocess.TimeoutExpired:
            p.kill()
            _, err = p.communicate()
            return ("timeout", time.monotonic() - t0, err[-300:])
    code = p.returncode
    if code < 0:
        code = "signal %d" % -code
    return (code, time.monotonic() - t0, err[-300:])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", required=True)
    ap.add_argument("--scenes", type=int, default=10000)
    ap.add_argument("--runs", type=int, default=10**9, help="most scenes also given to `run`")
    ap.add_argument("--recordings", type=int, default=2000)
    ap.add_argument("--timeout", type=float, default=20)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--seed", type=int, default=10)
    ap.add_argument("--keep", default="hostile-failures")
    a = ap.parse_args()
    work = tempfile.mkdtemp(prefix="contrail-hostile-")
    os.makedirs(a.keep, exist_ok=True)
    listing = subprocess.run([a.bin, "scenes"], capture_output=True, text=True).stdout.splitlines()
    # one scene per line (name, description); blank line and hint after them
    names = [l.split()[0] for l in listing if l.strip() and not l.startswith("(")]
    texts = {}
    for n in names:
        with open(os.path.join(os.path.dirname(__file__), "..", "scenes", n + ".toml"), "rb") as f:
            texts[n] = f.read()
    counts = collections.defaultdict(collections.Counter)
    slow = collections.Counter()
    bad = []
    rng = random.Random(a.seed)
    jobs = []
    for i in range(a.scenes):
        jobs.append(("scene", i, rng.choice(names), rng.randrange(2**32)))
    good = os.path.join(work, "good.mcap")
    subprocess.run([a.bin, "run", "crossing", "--quiet", "--set", "stepping.increments=12",
                    "--set", "stepping.end=0.3", "--out", good], check=False, capture_output=True)
    with open(good, "rb") as f:
        good_bytes = f.read()
    for i in range(a.recordings):
        jobs.append(("recording", i, None, rng.randrange(2**32)))
    rng.shuffle(jobs)  # partial results cover both kinds

    def one(job):
        kind, i, name, seed = job
        r = random.Random(seed)
        out = []
        if kind == "scene":
            path = os.path.join(work, "s%d.toml" % i)
            with open(path, "wb") as f:
                f.write(mutate_scene(texts[name], r))
            res = call([a.bin, "check", path], a.timeout)
            out.append(("check", path, res))
            if res[0] == 0 and i < a.runs:
                mc = os.path.join(work, "s%d.mcap" % i)
                res = call([a.bin, "run", path, "--quiet", "--out", mc], a.timeout)
                out.append(("run", path, res))
                for f in os.listdir(work):
                    if f.startswith(".s%d.mcap" % i) or f == "s%d.mcap" % i:
                        os.remove(os.path.join(work, f))
        else:
            path = os.path.join(work, "r%d.mcap" % i)
            with open(path, "wb") as f:
                f.write(damage_recording(good_bytes, r))
            out.append(("inspect", path, call([a.bin, "inspect", path], a.timeout)))
            out.append(("diff", path, call([a.bin, "diff", path, good], a.timeout)))
            rrd = os.path.join(work, "r%d.rrd" % i)
            out.append(("replay", path, call([a.bin, "replay", path, "--rerun-save", rrd], a.timeout)))
            out.append(("recover", path, call([a.bin, "recover", path, path + ".fixed.mcap"], a.timeout)))
        return out

    def report(done):
        n_scenes = sum(1 for j in jobs[:done] if j[0] == "scene")
        print("inputs: %d mutated scenes, %d damaged recordings, timeout %.0f s, %.0f s wall"
              % (n_scenes, done - n_scenes, a.timeout, time.monotonic() - t0))
        for verb in ["check", "run", "inspect", "diff", "replay", "recover"]:
            c = counts[verb]
            print("%-8s %6d  %s  (over 5 s: %d)" % (verb, sum(c.values()),
                  ", ".join("%s: %d" % (k, v) for k, v in sorted(c.items(), key=str)), slow[verb]))
        print("failures (exit not 0/1/2, or a panic, or no end after SIGINT): %d" % len(bad))
        for verb, keep, code, err in bad[:50]:
            print("  %s %s -> %s: %s" % (verb, keep, code, err.strip().splitlines()[-1:] if err.strip() else ""))
        sys.stdout.flush()

    t0 = time.monotonic()
    with cf.ThreadPoolExecutor(a.jobs) as ex:
        for k, results in enumerate(ex.map(one, jobs)):
            for verb, path, (code, secs, err) in results:
                counts[verb][code] += 1
                if secs > 5:
                    slow[verb] += 1
                ok = code in (0, 1, 2) or code == "sigint->130"
                if not ok or b"panicked" in err:
                    keep = os.path.join(a.keep, "%s-%d-%s" % (verb, k, os.path.basename(path)))
                    shutil.copy(path, keep)
                    bad.append((verb, keep, code, err.decode(errors="replace")))
            for verb, path, _ in results:
                if os.path.exists(path):
                    os.remove(path)
            if (k + 1) % 500 == 0:
                print("--- %d/%d done" % (k + 1, len(jobs)))
                report(k + 1)
    print("=== final")
    report(len(jobs))
    shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
