#!/usr/bin/env python3
"""Ratios of the 2026-11-26 sitting: reads engine_bench_2026-11-26_rounds.txt (the output of
engine_bench_2026-11-26_sitting.sh) and prints, per benchmark, each binary's particle_step_time per
round, its median, and the per-round ratios head/4992cc2 and head/5db094a with their median, min
and max (a ratio is taken within one round, where the runs were minutes apart). At-rest counters
are printed per binary, with a note when they differ between rounds.

    python3 docs/benchmarks/engine_bench_2026-11-26_ratios.py docs/benchmarks/engine_bench_2026-11-26_rounds.txt

A second argument names the binaries, head first, when a sitting named them otherwise:

    python3 docs/benchmarks/engine_bench_2026-11-26_ratios.py docs/benchmarks/engine_bench_2026-11-26_session5_rounds.txt head,5db
"""
import re
import statistics
import sys
from collections import defaultdict

SI = {"a": 1e-18, "f": 1e-15, "p": 1e-12, "n": 1e-9, "u": 1e-6, "m": 1e-3, "": 1.0, "k": 1e3,
      "M": 1e6}
BINARIES = ["head", "4992cc2", "5db094a"]
QUALITY = ("contacts", "kinetic_energy_per_particle", "kinetic_energy", "max_penetration",
           "velocity_passes", "position_passes", "outside", "divergences", "resets",
           "setup_seconds", "floor_ratio")


def number(text):
    """'3.95615ns' -> 3.95615 (ns), '2.57704us' -> 2577.04 (ns), '14.7813f' -> 1.47813e-14."""
    m = re.fullmatch(r"([-+0-9.eE]+)(ns|us|ms|ps|s|[afpnumkM]?)", text)
    if not m:
        return None
    value, suffix = float(m.group(1)), m.group(2)
    if suffix.endswith("s"):
        return value * {"ps": 1e-3, "ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}[suffix]
    return value * SI[suffix]


def parse(path):
    times = defaultdict(lambda: defaultdict(dict))  # bench -> binary -> round -> ns
    counters = defaultdict(lambda: defaultdict(dict))  # bench -> binary -> round -> {name: value}
    header, rnd, binary = [], None, None
    for line in open(path):
        m = re.match(r"# round (\d+) (\S+) (quick|slow) start", line)
        if m:
            rnd, binary = int(m.group(1)), m.group(2)
            continue
        if line.startswith("Benchmark"):
            header = line.split()[4:]  # after Benchmark Time CPU Iterations
            continue
        if not line.startswith("BM_") or rnd is None:
            continue
        tokens = line.split()
        name, values = tokens[0], tokens[6:]
        row = {}
        if len(values) >= len(header):  # a label may follow the counters
            for key, text in zip(header, values):
                row[key] = number(text)
        else:
            # Google Benchmark does not print a new header for a row with fewer counters than the
            # one above (the bandwidth floor under free fall): only its time per particle-step,
            # the one counter with a time unit, is read.
            row["particle_step_time"] = next(number(t) for t in values if t.endswith("s"))
        # A scene without particle_step_time (the rigid rain): its time per step, ns.
        if "particle_step_time" not in row:
            row["particle_step_time"] = number(tokens[1] + tokens[2])
        times[name][binary][rnd] = row["particle_step_time"]
        counters[name][binary][rnd] = row
    return times, counters


def main():
    times, counters = parse(sys.argv[1])
    if len(sys.argv) > 2:
        BINARIES[:] = sys.argv[2].split(",")
    print("particle_step_time (else the time per step), ns: per round (r1 r2 ...), median; ratios per round, median [min, max]")
    for name in times:
        print(f"\n{name}")
        for b in BINARIES:
            rounds = times[name].get(b, {})
            series = " ".join(f"{rounds[r]:.4g}" for r in sorted(rounds))
            med = statistics.median(rounds.values()) if rounds else float("nan")
            print(f"  {b:8s} {series}   median {med:.4g}")
        for other in BINARIES[1:]:
            head, base = times[name].get(BINARIES[0], {}), times[name].get(other, {})
            ratios = [head[r] / base[r] for r in sorted(head) if r in base]
            if ratios:
                print(f"  {BINARIES[0]}/{other}: " + " ".join(f"{x:.3f}" for x in ratios)
                      + f"   median {statistics.median(ratios):.3f} [{min(ratios):.3f}, {max(ratios):.3f}]")
        for b in BINARIES:
            rows = counters[name].get(b, {})
            if not rows:
                continue
            first = rows[min(rows)]
            parts = []
            for key in QUALITY:
                if key not in first:
                    continue
                values = sorted({row.get(key) for row in rows.values()})
                if key == "setup_seconds":
                    parts.append(f"{key} {min(values):.3g}-{max(values):.3g}")
                elif len(values) == 1:
                    parts.append(f"{key} {values[0]:.3g}")
                else:
                    parts.append(f"{key} {values[0]:.3g}..{values[-1]:.3g}")
            print(f"  at rest {b:8s} " + ", ".join(parts))


if __name__ == "__main__":
    main()
