#!/usr/bin/env python3
"""Merges the per-material tables of several `bench_evaluate_study hemisphere` reports into one.

A study of the 80 measured materials at 1600x1200 takes over two hours on two cores, so it runs
as parts (`--materials` lists), each writing its own report; this reads their per-material
tables (every rung's row, the chosen rung and the best by sphere marked) and prints the summary
over all materials, the per-material chosen and best rungs, and, with --beside, the chosen rung
of another report (e.g. the 400x300 study) for the same materials.

    merge_study_parts.py PART.md... [--beside OTHER.md] [--title TEXT] > MERGED.md
"""
import argparse
import statistics
import sys

ALBEDO_GOAL = 0.10  # relative directional-albedo error, as in the study's summary


def parse_report(path):
    """{material: {rung: row}} with row = dict(sphere, held, held_min, albedo, chosen, best)."""
    materials, current = {}, None
    with open(path, encoding="utf-8") as f:
        for line in f:
            if not line.startswith("| ") or line.startswith("|---"):
                continue
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if len(cells) != 11 or cells[0] == "material":
                continue
            if cells[0]:
                current = cells[0]
            label = cells[1]
            try:
                row = dict(sphere=float(cells[2]), held=float(cells[4]),
                           held_min=float(cells[5].split()[0]), albedo=float(cells[6]),
                           chosen="(chosen)" in label, best="(best)" in label)
            except ValueError:
                continue  # a rung that failed: no figures
            materials.setdefault(current, {})[label.split()[0]] = row
    if not materials:
        sys.exit(f"{path}: no per-material table found")
    return materials


def pick(rungs, key):
    for name, row in rungs.items():
        if row[key]:
            return name, row
    sys.exit(f"a material has no rung marked {key}")


def summary_line(label, rows):
    spheres = [r["sphere"] for _, r in rows]
    worst = min(rows, key=lambda mr: mr[1]["sphere"])
    within = sum(r["albedo"] <= ALBEDO_GOAL for _, r in rows)
    return (f"| {label} | {len(rows)} | {statistics.mean(spheres):.1f} | "
            f"{worst[1]['sphere']:.1f} ({worst[0]}) | "
            f"{statistics.mean(r['held'] for _, r in rows):.1f} | "
            f"{min(r['held_min'] for _, r in rows):.1f} | {within}/{len(rows)} |")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("parts", nargs="+")
    parser.add_argument("--beside")
    parser.add_argument("--title", default="Merged study")
    args = parser.parse_args()

    merged = {}
    for path in args.parts:
        for material, rungs in parse_report(path).items():
            if material in merged:
                sys.exit(f"{path}: {material} is in an earlier part too")
            merged[material] = rungs
    names = sorted(merged)
    beside = parse_report(args.beside) if args.beside else {}

    print(f"# {args.title}\n")
    print("Merged by `bench/merge_study_parts.py` from "
          + ", ".join(f"`{p}`" for p in args.parts) + " (each part's report has every rung's "
          "figures and its command).\n")
    print("| rung | materials | sphere mean (dB) | worst sphere (dB, material) | held-out mean (dB) "
          "| held-out min over views (dB) | albedo within 10 % |")
    print("|---|---|---|---|---|---|---|")
    rung_names = []
    for rungs in merged.values():
        rung_names += [r for r in rungs if r not in rung_names]
    for rung in rung_names:
        rows = [(m, merged[m][rung]) for m in names if rung in merged[m]]
        print(summary_line(rung, rows))
    print(summary_line("**validation-chosen**", [(m, pick(merged[m], "chosen")[1]) for m in names]))
    print(summary_line("**best by sphere**", [(m, pick(merged[m], "best")[1]) for m in names]))
    if beside:
        common = [m for m in names if m in beside]
        print(summary_line(f"chosen in `{args.beside}`",
                           [(m, pick(beside[m], "chosen")[1]) for m in common]))

    print("\n| material | chosen rung | sphere (dB) | held-out (dB) | albedo err | best rung | "
          "best sphere (dB) |" + (" chosen beside: rung | sphere (dB) | held-out (dB) | albedo err |"
                                  if beside else ""))
    print("|---|---|---|---|---|---|---|" + ("---|---|---|---|" if beside else ""))
    for m in names:
        cn, c = pick(merged[m], "chosen")
        bn, b = pick(merged[m], "best")
        line = (f"| {m} | {cn} | {c['sphere']:.1f} | {c['held']:.1f} | {c['albedo']:.3f} | {bn} | "
                f"{b['sphere']:.1f} |")
        if beside:
            if m in beside:
                on, o = pick(beside[m], "chosen")
                line += f" {on} | {o['sphere']:.1f} | {o['held']:.1f} | {o['albedo']:.3f} |"
            else:
                line += " | | | |"
        print(line)


if __name__ == "__main__":
    main()
