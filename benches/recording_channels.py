#!/usr/bin/env python3
"""What the bytes of an MCAP recording are, per channel: messages, raw bytes and the bytes
of the channel's messages compressed alone with zstd level 1 (a recording's chunks mix the
channels, so the sum is near, not equal to, the file's size).

    pip install mcap zstandard
    python3 benches/recording_channels.py full.mcap thin.mcap
"""
import collections
import sys

import zstandard
from mcap.reader import make_reader


def channels(path):
    raw, data, count = collections.Counter(), collections.defaultdict(list), collections.Counter()
    with open(path, "rb") as f:
        for _, channel, message in make_reader(f).iter_messages():
            raw[channel.topic] += len(message.data)
            data[channel.topic].append(message.data)
            count[channel.topic] += 1
    zstd = {t: len(zstandard.ZstdCompressor(level=1).compress(b"".join(m))) for t, m in data.items()}
    return raw, zstd, count


def main(paths):
    for path in paths:
        raw, zstd, count = channels(path)
        print(f"{path}\n| channel | messages | raw MB | zstd 1 MB |\n|---|---|---|---|")
        for t in sorted(raw, key=lambda t: -zstd[t]):
            print(f"| `{t}` | {count[t]} | {raw[t] / 1e6:.2f} | {zstd[t] / 1e6:.2f} |")
        print(f"| all | {sum(count.values())} | {sum(raw.values()) / 1e6:.2f} | {sum(zstd.values()) / 1e6:.2f} |")


if __name__ == "__main__":
    main(sys.argv[1:])
