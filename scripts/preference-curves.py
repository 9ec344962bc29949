#!/usr/bin/env python3
"""Learning curves per preference from one or more `cbtl experiment` folders (docs/domains-feeding.md).

Usage: scripts/preference-curves.py EXPERIMENT_DIR [EXPERIMENT_DIR...]

Every folder holds one folder per approach with one folder per seed (seed<N>/eval.csv), as `cbtl experiment
--out` writes them; folders given together are pooled (e.g. seeds 0..4 and 5..9 run apart). Prints Markdown:
the evaluation satisfaction per checkpoint (mean over seeds) and over all checkpoints (mean over seeds of each
seed's mean, ± standard error over seeds), then one table per preference column of eval.csv
(eval_<preference>_met_rate): the met rate per checkpoint, mean over seeds. A seed appearing in two folders of one
approach is an error. Standard library only.
"""
import csv
import math
import os
import sys


def read_runs(folders):
    runs = {}  # approach -> seed -> rows (dicts) in checkpoint order
    for folder in folders:
        if not os.path.isdir(folder):
            sys.exit(f"preference-curves: {folder} is not a folder")
        for approach in sorted(os.listdir(folder)):
            path = os.path.join(folder, approach)
            if not os.path.isdir(path):
                continue
            for seed in sorted(os.listdir(path)):
                csv_path = os.path.join(path, seed, "eval.csv")
                if not os.path.isfile(csv_path):
                    continue
                if seed in runs.setdefault(approach, {}):
                    sys.exit(f"preference-curves: {approach}/{seed} appears in more than one folder")
                with open(csv_path, newline="") as f:
                    runs[approach][seed] = list(csv.DictReader(f))
    if not runs:
        sys.exit("preference-curves: no <approach>/seed<N>/eval.csv under " + ", ".join(folders))
    return runs


def mean(values):
    return sum(values) / len(values)


def standard_error(values):
    if len(values) < 2:
        return 0.0
    m = mean(values)
    return math.sqrt(sum((v - m) ** 2 for v in values) / (len(values) - 1) / len(values))


def table(runs, column, steps, with_overall):
    header = "| approach | " + " | ".join(f"{s:,}" for s in steps)
    header += " | all checkpoints |" if with_overall else " |"
    lines = [header, "|---" * (len(steps) + 1 + (1 if with_overall else 0)) + "|"]
    for approach, seeds in runs.items():
        cells = []
        for k in range(len(steps)):
            values = [float(rows[k][column]) for rows in seeds.values() if k < len(rows)]
            cells.append(f"{mean(values):+.2f}" if with_overall else f"{mean(values):.2f}")
        line = f"| {approach} | " + " | ".join(cells)
        if with_overall:
            per_seed = [mean([float(r[column]) for r in rows]) for rows in seeds.values()]
            line += f" | {mean(per_seed):+.3f} ± {standard_error(per_seed):.3f} |"
        else:
            line += " |"
        lines.append(line)
    return "\n".join(lines)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    runs = read_runs(sys.argv[1:])
    first = next(iter(next(iter(runs.values())).values()))
    steps = [int(r["training_step"]) for r in first]
    seeds = sorted({len(s) for s in runs.values()})
    print(f"evaluation satisfaction ({'/'.join(map(str, seeds))} seeds per approach)\n")
    print(table(runs, "eval_mean_user_satisfaction", steps, True))
    preferences = [c[len("eval_"):-len("_met_rate")] for c in first[0] if c.startswith("eval_") and
                   c.endswith("_met_rate") and c not in ("eval_preferences_met_rate",)]
    for p in preferences:
        print(f"\n{p}: met rate per checkpoint (mean over seeds)\n")
        print(table(runs, f"eval_{p}_met_rate", steps, False))


if __name__ == "__main__":
    main()
