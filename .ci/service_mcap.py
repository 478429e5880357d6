"""Read a run's recording from `contrail serve` with HTTP range requests into Python's `mcap`
reader (as a remote MCAP reader such as Foxglove does): a seekable file object whose reads
are `Range: bytes=A-B` requests, so the reader seeks to the summary at the end first.

usage: service_mcap.py URL RUN_ID EXPECTED_INCREMENTS [TOKEN]
"""
import io
import json
import sys
import urllib.request

from mcap.reader import make_reader


class HttpRangeFile(io.RawIOBase):
    def __init__(self, url, token=None):
        self.url, self.pos, self.requests, self.partial = url, 0, 0, 0
        self.headers = {"Authorization": f"Bearer {token}"} if token else {}
        with self._get(0, 0) as r:
            self.size = int(r.headers["Content-Range"].split("/")[1])

    def _get(self, start, end):
        req = urllib.request.Request(self.url, headers={**self.headers, "Range": f"bytes={start}-{end}"})
        r = urllib.request.urlopen(req)
        self.requests += 1
        if r.status != 206:
            raise SystemExit(f"expected 206 Partial Content for a range request, got {r.status}")
        self.partial += 1
        return r

    def readable(self):
        return True

    def seekable(self):
        return True

    def tell(self):
        return self.pos

    def seek(self, offset, whence=io.SEEK_SET):
        base = {io.SEEK_SET: 0, io.SEEK_CUR: self.pos, io.SEEK_END: self.size}[whence]
        self.pos = max(0, base + offset)
        return self.pos

    def readinto(self, b):
        n = min(len(b), self.size - self.pos)
        if n <= 0:
            return 0
        with self._get(self.pos, self.pos + n - 1) as r:
            data = r.read()
        b[: len(data)] = data
        self.pos += len(data)
        return len(data)


def main():
    url, run_id, expected = sys.argv[1], sys.argv[2], int(sys.argv[3])
    token = sys.argv[4] if len(sys.argv) > 4 else None
    raw = HttpRangeFile(f"{url}/api/runs/{run_id}/recording", token)
    reader = make_reader(io.BufferedReader(raw, buffer_size=256 << 10))
    summary = reader.get_summary()
    assert summary is not None and summary.statistics is not None, "no summary section read"
    counts, outcome = {}, None
    for _schema, channel, message in reader.iter_messages():
        counts[channel.topic] = counts.get(channel.topic, 0) + 1
        if channel.topic == "/outcome":
            outcome = json.loads(message.data)
    assert counts.get("/increment") == expected, f"{counts.get('/increment')} increments, expected {expected}"
    assert outcome is not None and outcome["status"] == "completed", f"outcome {outcome}"
    assert summary.statistics.message_count == sum(counts.values())
    print(
        f"python mcap read {sum(counts.values())} messages ({len(counts)} topics) of {raw.size} bytes "
        f"through {raw.requests} range requests (all 206)"
    )


if __name__ == "__main__":
    main()
