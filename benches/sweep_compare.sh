#!/usr/bin/env bash
# A 50-point sweep: hapstab now (criterion, crates/hapstab/benches/sweep.rs, two threads as
# `hapstab sweep` runs) against the same bench file built on an earlier commit (default
# 82c07bd: an exact region per point), run alternately in the same session, with the ratios.
# Usage: bash benches/sweep_compare.sh [runs] [commit]   (default 5 runs; the median of the
# runs' criterion medians is reported)
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-5}
old=${2:-82c07bd}
wt="$PWD/target/sweep-compare-$old"
if [ ! -d "$wt" ]; then
  git worktree add --quiet --detach "$wt" "$old"
fi
mkdir -p "$wt/crates/hapstab/benches/common"
cp crates/hapstab/benches/sweep.rs "$wt/crates/hapstab/benches/sweep.rs"
cp crates/hapstab/benches/common/general_loop.rs "$wt/crates/hapstab/benches/common/general_loop.rs"
grep -q 'name = "sweep"' "$wt/crates/hapstab/Cargo.toml" ||
  printf '\n[[bench]]\nname = "sweep"\nharness = false\n' >> "$wt/crates/hapstab/Cargo.toml"
exe() { sed -n 's/.*Executable benches\/sweep.rs (\(.*\))/\1/p'; }
new_bin="$PWD/$(cargo bench -p hapstab --bench sweep --no-run 2>&1 | exe)"
old_bin="$wt/$(cd "$wt" && CARGO_TARGET_DIR="$wt/target" cargo bench -p hapstab --bench sweep --no-run 2>&1 | exe)"
out=target/sweep-compare; rm -rf "$out"; mkdir -p "$out"
for r in $(seq 1 "$runs"); do
  for which in old new; do
    bin=$old_bin; [ "$which" = new ] && bin=$new_bin
    "$bin" --bench --noplot --warm-up-time 1 --measurement-time 3 2>/dev/null |
      awk -v w="$which" -v o="$out" '
        /^sweep\// { name = $1; sub("sweep/", "", name) }
        /time:/ { for (i = 1; i <= NF; i++) if ($i ~ /^\[/) { v = $(i + 2); u = $(i + 3);
                  if (u == "ms") v *= 1e3; if (u == "s") v *= 1e6; print v >> (o "/" w "." name); break } }'
  done
done
python3 - "$out" "$old" "$(git rev-parse --short HEAD)" <<'PY'
import os, statistics, sys
out, old, head = sys.argv[1:4]
def med(f):
    xs = [float(x) for x in open(os.path.join(out, f))]
    return statistics.median(xs), min(xs), max(xs)
names = sorted({f.split(".", 1)[1] for f in os.listdir(out)})
print(f"| sweep (50 points) | {old} | {head} | ratio |")
print("|---|---|---|---|")
for n in names:
    o, n_ = med("old." + n), med("new." + n)
    print(f"| {n} | {o[0]/1e3:.2f} ms ({o[1]/1e3:.2f}-{o[2]/1e3:.2f}) | "
          f"{n_[0]/1e3:.2f} ms ({n_[1]/1e3:.2f}-{n_[2]/1e3:.2f}) | {o[0]/n_[0]:.1f}x |")
PY
