#!/usr/bin/env bash
# run-resolve-cases.sh — run `pdd resolve` on the cases of scripts/make-resolve-cases.sh and judge
# every written mesh with the independent exact checker scripts/check-resolution.py; print a table.
#   bash scripts/run-resolve-cases.sh DIR [PDD]     (PDD: the program, default build/bin/pdd)
# Environment: RESOLVE_OPTS extra options for `pdd resolve` (e.g. --max-rounds 50),
#              CHECK_OPTS extra options for the checker (e.g. --rho 1/4 --kappa 1/2),
#              CASES a space-separated subset of the case names,
#              CHECK_ONLY=1 judge the meshes already written in DIR/out (no pdd run).
# Writes DIR/out/<case>-{a,b}.msh, <case>.report.json (pdd's), <case>.check.json (the checker's),
# <case>.log, and DIR/out/table.txt. Columns: elements (A + B), pdd's exit code, rounds (rows of
# the report's rounds table), cost (the checker's SPEC §11 mesh object norm, summed over A and B),
# rigid (the cost of the smallest separating translation of B, or of body 1 with --self, along
# the case's direction: t^2 when A is fixed, t^2/2 split between both), cost/rigid, the smallest
# V1/V0 and eta1/eta0, the checker's R1-R4 verdicts, whether pdd's own verdicts (r1-r3, and r4
# when its report has one) agree with them,
# pdd's time and the checker's time (R1-R4 and cost; the rigid bisection apart).
set -uo pipefail
D=${1:?usage: run-resolve-cases.sh DIR [PDD]}
PDD=${2:-build/bin/pdd}
cd "$(dirname "$0")/.."
O="$D/out"
mkdir -p "$O"
while IFS=$'\t' read -r name ropts copts; do
  if [ -n "${CASES:-}" ] && [[ " $CASES " != *" $name "* ]]; then continue; fi
  outs="--out-a $O/$name-a.msh"; couts="--a-out $O/$name-a.msh"
  # the checker reads the same inputs as pdd: --a X [--b Y] [--self] [--fix f]
  cin=$(echo "$ropts" | sed 's/--fix [ab]//')
  if [[ "$ropts" == *"--b "* ]]; then outs="$outs --out-b $O/$name-b.msh"; couts="$couts --b-out $O/$name-b.msh"; fi
  echo "run-resolve-cases: $name" >&2
  if [ -z "${CHECK_ONLY:-}" ]; then
    t0=$(date +%s%N)
    # shellcheck disable=SC2086
    $PDD resolve $ropts $outs --report "$O/$name.report.json" --quiet ${RESOLVE_OPTS:-} > "$O/$name.log" 2>&1
    rc=$?
    ms=$(( ($(date +%s%N) - t0) / 1000000 ))
    printf '{"exit": %d, "seconds": %d.%03d}\n' "$rc" $((ms / 1000)) $((ms % 1000)) > "$O/$name.run.json"
  fi
  # shellcheck disable=SC2086
  /usr/bin/python3 scripts/check-resolution.py $cin $couts $copts ${CHECK_OPTS:-} \
    > "$O/$name.check.json" 2>> "$O/$name.log"
done < "$D/cases.tsv"

/usr/bin/python3 - "$D" <<'PY' | tee "$O/table.txt"
import json, os, sys
D = sys.argv[1]
O = os.path.join(D, "out")
def load(p):
    try:
        with open(p) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None
cols = ["case", "elements", "exit", "rounds", "cost", "rigid", "cost/rigid", "min V1/V0",
        "min eta1/eta0", "R1", "R2", "R3", "R4", "pdd agrees", "pdd s", "check s", "rigid s"]
rows = []
for line in open(os.path.join(D, "cases.tsv")):
    name = line.split("\t")[0]
    c, r, run = (load(os.path.join(O, f"{name}.{k}.json")) for k in ("check", "report", "run"))
    if c is None or run is None:
        continue
    el = "+".join(str(m["elements"]) for m in c["per_mesh"].values())
    rig = c.get("rigid", {}).get("cost")
    f = lambda x, d=3: "-" if x is None else f"{x:.{d}g}"
    # pdd's own verdicts (r4 once it reports one) against the checker's
    keys = [k for k in ("r1", "r2", "r3", "r4") if r is not None and k in r]
    agree = "-" if r is None else ("yes" if all(r[k] == c[k] for k in keys) else "NO")
    rows.append([name, el, str(run["exit"]), "-" if r is None else str(len(r.get("rounds", []))),
                 f(c["cost"]), f(rig), f(c["cost"] / rig if rig else None),
                 f(c["min_volume_ratio"]), f(c["min_shape_ratio"]),
                 *["ok" if c[k] else f"FAIL" for k in ("r1", "r2", "r3", "r4")],
                 agree, f(run["seconds"]), f(c["seconds"]["total"]), f(c["seconds"].get("rigid"))])
    for k, n in (("r1", "intersecting_pairs"), ("r2", "inverted_or_flat_count"),
                 ("r3", "moved_fixed_count"), ("r4", "r4_failing_count")):
        if not c[k]:
            rows[-1][cols.index(k.upper())] = f"FAIL({c[n]})"
w = [max(len(x[i]) for x in rows + [cols]) for i in range(len(cols))]
print("| " + " | ".join(h.ljust(w[i]) for i, h in enumerate(cols)) + " |")
print("|" + "|".join("-" * (x + 2) for x in w) + "|")
for x in rows:
    print("| " + " | ".join(v.ljust(w[i]) for i, v in enumerate(x)) + " |")
PY
