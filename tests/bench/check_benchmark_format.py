#!/usr/bin/env python3
"""nenrin_bench honours Google Benchmark's standard output flags (issue 17): with
--benchmark_format=json its stdout is JSON that json.load reads, with the contract names
(no "/real_time" suffix); --benchmark_out with --benchmark_out_format=csv writes CSV; the
console output carries no colour codes when it is not a terminal. A tiny benchmark case runs
once (this checks formats, not timings). Usage: check_benchmark_format.py NENRIN_BENCH"""
import csv
import json
import os
import subprocess
import sys
import tempfile

bench = sys.argv[1]
case = ["--benchmark_filter=^BM_GrowthField/100/1/", "--benchmark_min_time=0.001"]

def run(*args):
    r = subprocess.run([bench, *case, *args], capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        sys.exit(f"{bench} {' '.join(args)} failed ({r.returncode}): {r.stderr}")
    return r.stdout

doc = json.loads(run("--benchmark_format=json"))
names = [b["name"] for b in doc["benchmarks"]]
assert names == ["BM_GrowthField/100/1"], f"JSON benchmark names {names}"
assert doc["benchmarks"][0]["real_time"] > 0, "JSON has no time"

with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "out.csv")
    console = run(f"--benchmark_out={out}", "--benchmark_out_format=csv")
    rows = list(csv.reader(l for l in open(out) if not l.startswith(("-", "Run", "CPU", "Load", "*"))))
    header = next(i for i, r in enumerate(rows) if r and r[0] == "name")
    got = [r[0] for r in rows[header + 1:] if r]
    assert got == ["BM_GrowthField/100/1"], f"CSV names {got}"
    assert "\x1b[" not in console, "colour codes in console output that is not a terminal"
    assert "BM_GrowthField/100/1 " in console, f"console output: {console}"
print("nenrin_bench: JSON, CSV and plain console output with the contract names")
