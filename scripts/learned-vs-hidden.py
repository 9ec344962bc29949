#!/usr/bin/env python3
"""What an approach learned in a robot-domain experiment, against the hidden simulated user (docs/results.md).

Usage: scripts/learned-vs-hidden.py books|cleaning|feeding EXPERIMENT_DIR [APPROACH...]

For every seed folder of each APPROACH (default: every approach folder in EXPERIMENT_DIR) it reads the last
model snapshot (models/<last step>.json) and the last evaluation (eval.csv).

books: the handoverInROM interval's version space (the lower bound lies in [x1, x2], the upper in [x3, x4]: the
  interval model's trapezoid, runtime/model/IntervalModel.h) and whether both lie within 2 cm of the hidden range
  of motion [0.1, 0.3] m; and the share of final-evaluation episodes with satisfaction +1 (the first book handed
  over was enjoyed and reached; each evaluation task offers one enjoyed book among five), a lower bound on how
  often an enjoyed book is picked first.
cleaning: whether the surfacePreferred table equals the hidden one (only shelfMiddle and sideTable0 welcome), and
  which surfaces were never labelled.
feeding: what each checkpoint's models/<step>.json knows of the user's occlusion sensitivity (the occlusionFree
  threshold; the hidden user's is 0.05): the version space [highest score the user let pass, lowest they
  complained about] and the threshold model's verdict there (it accepts a score up to the middle, where P(holds)
  = 0.5; runtime/model/ThresholdModel.h); per approach and checkpoint, mean over seeds: the width of the version
  space, the verdict's distance from the hidden threshold, and the share of 1,001 scores evenly spread over
  0 .. 0.1 (the range the arm's configurations take in this scene) on which the model's verdict is the user's.
  Unlike the evaluation's met rates this measures what was learned, not whether a choice happened to pass: a
  robot that keeps far below the user's threshold meets the preference without knowing it.
Standard library only.
"""
import csv
import json
import math
import os
import sys

ROM_LOW, ROM_HIGH, ROM_TOLERANCE = 0.1, 0.3, 0.02
SURFACES = ["mainTable", "shelfBottom", "shelfMiddle", "shelfTop", "sideTable0", "sideTable1", "sideTable2"]
WELCOME = {"shelfMiddle", "sideTable0"}


def last_snapshot(run):
    steps = sorted(int(f[:-5]) for f in os.listdir(os.path.join(run, "models")) if f.endswith(".json"))
    with open(os.path.join(run, "models", f"{steps[-1]}.json")) as f:
        return json.load(f)


def final_eval(run):
    with open(os.path.join(run, "eval.csv")) as f:
        last = list(csv.DictReader(f))[-1]
    return [float(v) for k, v in last.items() if k.startswith("eval_episode_") and not math.isnan(float(v))]


def trapezoid(points, lo, hi):
    positives = [x for x, holds in points if holds]
    if not positives:
        return lo, lo, hi, hi
    x2, x3 = min(positives), max(positives)
    # Negatives between positives contradict them and are left out, as the model does.
    below = [x for x, holds in points if not holds and x < x2]
    above = [x for x, holds in points if not holds and x > x3]
    return (max(below) if below else lo), x2, x3, (min(above) if above else hi)


def books(approach, runs):
    within, episodes, satisfied = 0, 0, 0
    print(f"{approach}: seed   x1      x2      x3      x4      ROM within 2 cm   final eval +1")
    for seed, run in runs:
        interval = last_snapshot(run)["generators"].get("handoverInROM", {}).get("", {}).get("interval", {})
        x1, x2, x3, x4 = trapezoid(interval.get("data", []), 0.0, 1.25)
        ok = all(abs(x - ROM_LOW) <= ROM_TOLERANCE for x in (x1, x2)) and all(
            abs(x - ROM_HIGH) <= ROM_TOLERANCE for x in (x3, x4))
        within += ok
        values = final_eval(run)
        plus = sum(1 for v in values if v > 0)
        episodes += len(values)
        satisfied += plus
        print(f"  {seed:6} {x1:.4f}  {x2:.4f}  {x3:.4f}  {x4:.4f}  {'yes' if ok else 'no':17} {plus}/{len(values)}")
    print(f"  ROM recovered within 2 cm: {within}/{len(runs)} seeds; final evaluations with satisfaction +1: "
          f"{satisfied}/{episodes} ({100.0 * satisfied / max(episodes, 1):.1f} %)")


def cleaning(approach, runs):
    exact = 0
    print(f"{approach}: seed   table equals the hidden user   never labelled")
    for seed, run in runs:
        table = last_snapshot(run)["generators"].get("surfacePreferred", {}).get("", {}).get("table", {})
        entries = table.get("entries", {})
        same = all(entries.get(s) == (s in WELCOME) for s in SURFACES)
        exact += same
        missing = [s for s in SURFACES if s not in entries]
        print(f"  {seed:6} {'yes' if same else 'no':30} {' '.join(missing) or '-'}")
    print(f"  learned table equals the hidden one: {exact}/{len(runs)} seeds")


HIDDEN_OCCLUSION = 0.05
SCORE_GRID = [0.1 * i / 1000 for i in range(1001)]


def occlusion_knowledge(snapshot):
    """(version-space width, |verdict - hidden|, accuracy over SCORE_GRID) of one profile's occlusion model."""
    model = snapshot["generators"].get("occlusionFree", {}).get("", {}).get("threshold", {})
    lo, hi = model.get("lo", 0.0), model.get("hi", 1.0)
    for score, holds in model.get("data", []):  # direction "below": holds => threshold >= score
        if holds:
            lo = max(lo, score)
        else:
            hi = min(hi, score)
    verdict = (lo + hi) / 2 if lo < hi else lo
    correct = sum(1 for x in SCORE_GRID if (x <= verdict) == (x < HIDDEN_OCCLUSION))
    return hi - lo, abs(verdict - HIDDEN_OCCLUSION), correct / len(SCORE_GRID)


def feeding(approach, runs):
    by_step = {}
    for _, run in runs:
        folder = os.path.join(run, "models")
        for name in os.listdir(folder):
            if name.endswith(".json"):
                with open(os.path.join(folder, name)) as f:
                    by_step.setdefault(int(name[:-5]), []).append(occlusion_knowledge(json.load(f)))
    print(f"{approach}: occlusion threshold, mean over {len(runs)} seeds")
    print("    step   version-space width   |verdict - 0.05|   verdict = user's on 0..0.1")
    for step in sorted(by_step):
        rows = by_step[step]
        mean = [sum(r[k] for r in rows) / len(rows) for k in range(3)]
        print(f"  {step:6}   {mean[0]:19.4f}   {mean[1]:16.4f}   {mean[2]:26.3f}")


def main():
    if len(sys.argv) < 3 or sys.argv[1] not in ("books", "cleaning", "feeding"):
        sys.exit(__doc__)
    root = sys.argv[2]
    approaches = sys.argv[3:] or sorted(
        d for d in os.listdir(root) if os.path.isdir(os.path.join(root, d)) and not d.startswith("."))
    for approach in approaches:
        folder = os.path.join(root, approach)
        # Trial folders only (seed0, seed1, ...): files beside them, such as an audit's report, are not trials.
        seeds = sorted((d for d in os.listdir(folder)
                        if d.startswith("seed") and d[4:].isdigit() and os.path.isdir(os.path.join(folder, d))),
                       key=lambda d: int(d[4:]))
        runs = [(seed, os.path.join(folder, seed)) for seed in seeds]
        {"books": books, "cleaning": cleaning, "feeding": feeding}[sys.argv[1]](approach, runs)


if __name__ == "__main__":
    main()
