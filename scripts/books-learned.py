#!/usr/bin/env python3
"""What CBTL learned in a Books experiment, against the hidden user (docs/results.md, Books).

Usage: scripts/books-learned.py EXPERIMENT_DIR [APPROACH]

For every seed folder of APPROACH (default cbtl) it reads the last model snapshot (models/<last step>.json) and the
last evaluation (eval.csv), and prints:
  - the handoverInROM interval's version space: the lower bound lies in [x1, x2], the upper in [x3, x4] (the
    interval model's trapezoid, runtime/model/IntervalModel.h), and whether both lie within 2 cm of the hidden
    range of motion [0.1, 0.3] m;
  - the share of final-evaluation episodes with satisfaction +1: the first book handed over was enjoyed and
    reached (each evaluation task offers one enjoyed book among five), a lower bound on how often an enjoyed book
    is picked first.
Standard library only.
"""
import csv
import json
import math
import os
import sys

HIDDEN_LOW, HIDDEN_HIGH, TOLERANCE = 0.1, 0.3, 0.02


def trapezoid(points, lo, hi):
    positives = [x for x, holds in points if holds]
    if not positives:
        return lo, lo, hi, hi
    x2, x3 = min(positives), max(positives)
    # Negatives between positives contradict them and are left out, as the model does.
    below = [x for x, holds in points if not holds and x < x2]
    above = [x for x, holds in points if not holds and x > x3]
    return (max(below) if below else lo), x2, x3, (min(above) if above else hi)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    root = sys.argv[1]
    approach = sys.argv[2] if len(sys.argv) > 2 else "cbtl"
    folder = os.path.join(root, approach)
    seeds = sorted((d for d in os.listdir(folder) if d.startswith("seed")), key=lambda d: int(d[4:]))
    within, episodes, satisfied = 0, 0, 0
    print("seed   x1      x2      x3      x4      ROM within 2 cm   final eval +1")
    for seed in seeds:
        run = os.path.join(folder, seed)
        steps = sorted(int(f[:-5]) for f in os.listdir(os.path.join(run, "models")) if f.endswith(".json"))
        with open(os.path.join(run, "models", f"{steps[-1]}.json")) as f:
            profile = json.load(f)
        points = profile["generators"]["handoverInROM"][""]["interval"]["data"]
        x1, x2, x3, x4 = trapezoid(points, 0.0, 1.25)
        ok = all(abs(x - HIDDEN_LOW) <= TOLERANCE for x in (x1, x2)) and all(
            abs(x - HIDDEN_HIGH) <= TOLERANCE for x in (x3, x4))
        within += ok
        with open(os.path.join(run, "eval.csv")) as f:
            last = list(csv.DictReader(f))[-1]
        values = [float(v) for k, v in last.items() if k.startswith("eval_episode_") and not math.isnan(float(v))]
        plus = sum(1 for v in values if v > 0)
        episodes += len(values)
        satisfied += plus
        print(f"{seed:6} {x1:.4f}  {x2:.4f}  {x3:.4f}  {x4:.4f}  {'yes' if ok else 'no':17} {plus}/{len(values)}")
    print(f"ROM recovered within 2 cm: {within}/{len(seeds)} seeds; final evaluations with satisfaction +1: "
          f"{satisfied}/{episodes} ({100.0 * satisfied / max(episodes, 1):.1f} %)")


if __name__ == "__main__":
    main()
