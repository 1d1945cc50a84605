#!/usr/bin/env bash
# Every margin of one wall: hapstab (criterion, crates/hapstab/benches/margins.rs, the two
# threads the margins use) against python-control's stability_margins on the same sampled
# loops (benches/baseline/margins_baseline.py), in the same run, with the ratios.
# Usage: bash benches/margins_compare.sh [runs]   (criterion runs, default 5; the median of
# the runs' medians is reported; installs python-control into a venv under target/ if needed)
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-5}
venv=target/baseline-venv
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
"$venv/bin/python" -c "import control" 2>/dev/null || "$venv/bin/pip" install --quiet numpy scipy control
out=target/margins-compare; rm -rf "$out"; mkdir -p "$out"
for r in $(seq 1 "$runs"); do
  cargo bench -p hapstab --bench margins -- --noplot --warm-up-time 1 --measurement-time 4 >/dev/null 2>&1
  for f in target/criterion/margins/*/*/new/estimates.json; do
    id=$(echo "$f" | sed 's|target/criterion/margins/||; s|/new/estimates.json||; s|/|.|')
    python3 -c "import json;print(json.load(open('$f'))['median']['point_estimate'])" >> "$out/$id"
  done
done
env OPENBLAS_NUM_THREADS=1 "$venv/bin/python" benches/baseline/margins_baseline.py > "$out/python-control.txt"
python3 - "$out" <<'PY'
import os, re, statistics, sys
out = sys.argv[1]
pc = {}
for line in open(os.path.join(out, "python-control.txt")):
    m = re.match(r"\s*(\S+(?: 6)?)\s+d\s*=\s*(\d+).*?([\d.]+)\s*ms", line)
    if m:
        pc[(m.group(1), int(m.group(2)))] = float(m.group(3))
print(open(os.path.join(out, "python-control.txt")).read())
print("| loop | hapstab (median of runs; range) | python-control | ratio |")
print("|---|---|---|---|")
for name, key, d in (("paper", "paper_loop", 0), ("paper", "paper_loop", 1),
                     ("paper", "paper_loop", 10), ("order 6", "order_6_loop", 10)):
    xs = [float(x) / 1e3 for x in open(os.path.join(out, f"{key}.{d}"))]
    med = statistics.median(xs)
    p = pc.get((name, d))
    ratio = f"{p * 1e3 / med:.0f}x" if p else "n/a"
    pcs = f"{p:.1f} ms" if p else "n/a"
    print(f"| {name}, d = {d} | {med:.1f} µs ({min(xs):.1f}-{max(xs):.1f}) | {pcs} | {ratio} |")
PY
